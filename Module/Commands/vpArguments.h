#ifndef vpArguments_h
#define vpArguments_h

#include <map>
#include <set>
#include <string>
#include <vector>

namespace vp
{
/// Minimal option parser for the subcommands: "--name value", "--name=value" and "--flag".
/// Unknown options and missing values throw InputError naming the option.
class Arguments
{
public:
  Arguments(const std::vector<std::string>& args, const std::set<std::string>& valueOptions,
    const std::set<std::string>& flagOptions);

  bool Has(const std::string& name) const { return this->Values.count(name) > 0; }
  std::string Get(const std::string& name, const std::string& fallback = std::string()) const;
  double GetNumber(const std::string& name, double fallback) const;
  /// A whole number of at least minimum (default 1); throws InputError naming the option.
  int GetInteger(const std::string& name, int fallback, int minimum = 1) const;
  const std::vector<std::string>& Positional() const { return this->Positionals; }

private:
  std::map<std::string, std::string> Values;
  std::vector<std::string> Positionals;
};

/// True when args ask for help (--help or -h anywhere).
bool WantsHelp(const std::vector<std::string>& args);

/// Splits text at every separator, empty items kept ("a,,b" -> "a", "", "b"; "" -> "").
std::vector<std::string> SplitList(const std::string& text, char separator);

/// Splits "a=b,c=d" into pairs; throws InputError(option, ...) on a malformed entry.
std::vector<std::pair<std::string, std::string>> ParsePairs(const std::string& text, const std::string& option);
} // namespace vp

#endif
