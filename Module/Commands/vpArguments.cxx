#include "vpArguments.h"

#include "vpDecimal.h"
#include "vpInputError.h"

#include <cmath>
#include <cstdlib>

namespace vp
{
Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& valueOptions,
  const std::set<std::string>& flagOptions)
{
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    std::string arg = args[i];
    if (arg.size() < 2 || arg[0] != '-')
    {
      this->Positionals.push_back(arg);
      continue;
    }
    std::string value;
    bool inlineValue = false;
    const std::size_t eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos)
    {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
      inlineValue = true;
    }
    if (flagOptions.count(arg))
    {
      if (inlineValue)
      {
        throw InputError(arg, "takes no value");
      }
      this->Values[arg] = "1";
    }
    else if (valueOptions.count(arg))
    {
      if (!inlineValue)
      {
        if (i + 1 >= args.size())
        {
          throw InputError(arg, "needs a value");
        }
        value = args[++i];
      }
      this->Values[arg] = value;
    }
    else
    {
      throw InputError(arg, "unknown option (see --help)");
    }
  }
}

std::string Arguments::Get(const std::string& name, const std::string& fallback) const
{
  const auto it = this->Values.find(name);
  return it == this->Values.end() ? fallback : it->second;
}

double Arguments::GetNumber(const std::string& name, double fallback) const
{
  if (!this->Has(name))
  {
    return fallback;
  }
  const std::string text = this->Get(name);
  const char* end = ScanDecimal(text.c_str());
  const double v = std::strtod(text.c_str(), nullptr);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
  {
    throw InputError(name, "expected a number, got '" + text + "'");
  }
  return v;
}

int Arguments::GetInteger(const std::string& name, int fallback, int minimum) const
{
  if (!this->Has(name))
  {
    return fallback;
  }
  const std::string text = this->Get(name);
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < minimum || v > 1000000000L)
  {
    throw InputError(name, (minimum == 1 ? std::string("expected a positive whole number")
                                         : "expected a whole number of at least " + std::to_string(minimum)) +
        ", got '" + text + "'");
  }
  return static_cast<int>(v);
}

bool WantsHelp(const std::vector<std::string>& args)
{
  for (const auto& a : args)
  {
    if (a == "--help" || a == "-h")
    {
      return true;
    }
  }
  return false;
}

std::vector<std::string> SplitList(const std::string& text, char separator)
{
  std::vector<std::string> items;
  std::size_t start = 0;
  for (std::size_t at = text.find(separator); at != std::string::npos; at = text.find(separator, start))
  {
    items.push_back(text.substr(start, at - start));
    start = at + 1;
  }
  items.push_back(text.substr(start));
  return items;
}

std::vector<std::pair<std::string, std::string>> ParsePairs(const std::string& text, const std::string& option)
{
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& entry : SplitList(text, ','))
  {
    const std::size_t eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
    {
      throw InputError(option, "expected CLASS=FILE, got '" + entry + "'");
    }
    pairs.emplace_back(entry.substr(0, eq), entry.substr(eq + 1));
  }
  return pairs;
}
} // namespace vp
