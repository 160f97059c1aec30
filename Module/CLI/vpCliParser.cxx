// A command line read against its description.
#include "vpCliDescription.h"
#include "vpCliValues.h"
#include "vpOutputGuard.h"

#include "vpInputError.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace vp
{
namespace cli
{
//----------------------------------------------------------------------------
const Parameter& ParsedArguments::Declared(const std::string& name) const
{
  return this->Description->Find(name);
}

bool ParsedArguments::IsSet(const std::string& name) const
{
  this->Declared(name);
  return this->Values.count(name) > 0;
}

std::string ParsedArguments::GetString(const std::string& name) const
{
  const Parameter& p = this->Declared(name);
  const auto it = this->Values.find(name);
  return it == this->Values.end() ? p.GetDefault() : it->second;
}

double ParsedArguments::GetNumber(const std::string& name) const
{
  double value = 0.0;
  if (!ParseDouble(this->GetString(name), value))
  {
    throw std::logic_error(name + ": not a number and no default");
  }
  return value;
}

int ParsedArguments::GetInteger(const std::string& name) const
{
  return static_cast<int>(std::lround(this->GetNumber(name)));
}

bool ParsedArguments::GetBoolean(const std::string& name) const
{
  return this->GetString(name) == "true";
}

std::vector<double> ParsedArguments::GetNumbers(const std::string& name) const
{
  std::vector<double> numbers;
  const std::string text = this->GetString(name);
  if (!text.empty() && !ParseNumberList(text, numbers))
  {
    throw std::logic_error(name + ": not a list of numbers");
  }
  return numbers;
}

std::array<double, 3> ParsedArguments::GetPoint(const std::string& name) const
{
  const std::vector<double> numbers = this->GetNumbers(name);
  if (numbers.size() != 3)
  {
    throw std::logic_error(name + ": no point given and no default");
  }
  return { numbers[0], numbers[1], numbers[2] };
}

std::vector<std::string> ParsedArguments::GetStrings(const std::string& name) const
{
  this->Declared(name);
  const auto many = this->Multiple.find(name);
  if (many != this->Multiple.end())
  {
    return many->second;
  }
  const std::string value = this->GetString(name);
  return value.empty() ? std::vector<std::string>() : std::vector<std::string>{ value };
}

namespace
{
/// One argument that starts with a dash: "--key=value" split, else the key alone.
struct FlagArgument
{
  std::string Key, Value;
  bool InlineValue = false;

  explicit FlagArgument(const std::string& arg)
    : Key(arg)
  {
    const std::size_t eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos)
    {
      this->Key = arg.substr(0, eq);
      this->Value = arg.substr(eq + 1);
      this->InlineValue = true;
    }
  }
};

/// Reads a command line against a table: parameters found by "-f" and "--longflag", the rest
/// given to the index parameters in order.
class CommandLineReader
{
public:
  explicit CommandLineReader(const ModuleDescription& description);
  void Read(const std::vector<std::string>& args);

  std::map<std::string, std::string> Values;
  std::map<std::string, std::vector<std::string>> Multiple;
  std::string ReturnParameterFile;

private:
  std::string TakeValue(const std::vector<std::string>& args, std::size_t& i, const FlagArgument& flag) const;
  void ReadFlag(const std::vector<std::string>& args, std::size_t& i);
  void ReadIndexed(const std::vector<std::string>& positionals);
  void CheckRequired() const;

  const ModuleDescription& Description;
  std::map<std::string, const Parameter*> ByFlag;
  std::vector<const Parameter*> Indexed;
};

CommandLineReader::CommandLineReader(const ModuleDescription& description)
  : Description(description)
  , Indexed(description.IndexParameters())
{
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (!p.GetFlag().empty())
      {
        this->ByFlag["-" + p.GetFlag()] = &p;
      }
      if (!p.GetLongFlag().empty())
      {
        this->ByFlag["--" + p.GetLongFlag()] = &p;
      }
    }
  }
}

void CommandLineReader::Read(const std::vector<std::string>& args)
{
  std::vector<std::string> positionals;
  bool optionsEnded = false;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (optionsEnded || arg.size() < 2 || arg[0] != '-')
    {
      positionals.push_back(arg);
    }
    else if (arg == "--")
    {
      optionsEnded = true;
    }
    else
    {
      this->ReadFlag(args, i);
    }
  }
  this->ReadIndexed(positionals);
  this->CheckRequired();
}

/// The value of the flag at args[i]: inline, or the next argument, which it consumes.
std::string CommandLineReader::TakeValue(const std::vector<std::string>& args, std::size_t& i, const FlagArgument& flag) const
{
  if (flag.InlineValue)
  {
    return flag.Value;
  }
  if (i + 1 >= args.size())
  {
    throw UsageError(flag.Key, "needs a value");
  }
  return args[++i];
}

void CommandLineReader::ReadFlag(const std::vector<std::string>& args, std::size_t& i)
{
  const FlagArgument flag(args[i]);
  if (flag.Key == "--returnparameterfile")
  {
    const std::string file = this->TakeValue(args, i, flag);
    if (!this->ReturnParameterFile.empty() || file.empty())
    {
      throw UsageError(flag.Key, "give one file, once");
    }
    this->ReturnParameterFile = file;
    return;
  }
  const auto found = this->ByFlag.find(flag.Key);
  if (found == this->ByFlag.end())
  {
    throw UsageError(flag.Key, "unknown option (see " + this->Description.Program + " --help)");
  }
  const Parameter& p = *found->second;
  if (p.GetType() == ParameterType::Boolean && flag.InlineValue)
  {
    throw UsageError(flag.Key, "is a switch and takes no value: give it for true, leave it out for false");
  }
  const std::string value = p.GetType() == ParameterType::Boolean ? "true" : this->TakeValue(args, i, flag);
  if (this->Values.count(p.GetName()))
  {
    throw UsageError(flag.Key, "given twice");
  }
  CheckValue(p, value);
  this->Values[p.GetName()] = value;
}

void CommandLineReader::ReadIndexed(const std::vector<std::string>& positionals)
{
  const bool takesRest = !this->Indexed.empty() && this->Indexed.back()->IsMultiple();
  if (positionals.size() > this->Indexed.size() && !takesRest)
  {
    throw UsageError(positionals[this->Indexed.size()],
      "unexpected argument (" + this->Description.Program + " takes " + std::to_string(this->Indexed.size()) +
        " without a flag; see --help)");
  }
  for (std::size_t k = 0; k < positionals.size(); ++k)
  {
    const Parameter& p = *this->Indexed[std::min(k, this->Indexed.size() - 1)];
    CheckValue(p, positionals[k]);
    this->Values.emplace(p.GetName(), positionals[k]);
    if (p.IsMultiple())
    {
      this->Multiple[p.GetName()].push_back(positionals[k]);
    }
  }
}

void CommandLineReader::CheckRequired() const
{
  for (const auto& group : this->Description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (p.IsRequired() && !this->Values.count(p.GetName()))
      {
        throw UsageError(p.DisplayName(), "is required (" +
            (p.GetLabel().empty() ? "see " + this->Description.Program + " --help" : p.GetLabel()) + ")");
      }
    }
  }
}
} // namespace

ParsedArguments ParseArguments(const ModuleDescription& description, const std::vector<std::string>& args)
{
  CommandLineReader reader(description);
  reader.Read(args);
  ParsedArguments parsed;
  parsed.Description = &description;
  parsed.Values = std::move(reader.Values);
  parsed.Multiple = std::move(reader.Multiple);
  parsed.ReturnParameterFile = std::move(reader.ReturnParameterFile);
  RefuseOutputsOverInputs(description, parsed.Values, parsed.Multiple, parsed.ReturnParameterFile);
  return parsed;
}
} // namespace cli
} // namespace vp
