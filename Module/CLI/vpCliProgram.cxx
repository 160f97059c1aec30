// The life of a program around its description: --xml, --help, parsing, the body, the exit code
// and the return-parameter file.
#include "vpCliDescription.h"
#include "vpOutputFile.h"
#include "vpCliValues.h"

#include "vpInputError.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <iostream>
#include <new>

namespace vp
{
namespace cli
{
namespace
{
/// Routes one stream into another for a scope (exception safe).
class StreamRedirect
{
public:
  StreamRedirect(std::ostream& stream, std::streambuf* target)
    : Stream(stream)
    , Saved(stream.rdbuf(target))
  {
  }
  ~StreamRedirect() { this->Stream.rdbuf(this->Saved); }
  StreamRedirect(const StreamRedirect&) = delete;
  StreamRedirect& operator=(const StreamRedirect&) = delete;

private:
  std::ostream& Stream;
  std::streambuf* Saved;
};
} // namespace

//----------------------------------------------------------------------------
ReturnValues::ReturnValues(const ModuleDescription& description)
  : Description(&description)
{
}

void ReturnValues::Set(const std::string& name, const std::string& value)
{
  const Parameter& p = this->Description->Find(name);
  if (!p.IsReturnParameter())
  {
    throw std::logic_error(name + ": not a return parameter");
  }
  // One line per value: the file is read line by line.
  std::string line = value;
  std::replace(line.begin(), line.end(), '\n', ' ');
  std::replace(line.begin(), line.end(), '\r', ' ');
  const bool emptyAllowed = p.GetType() == ParameterType::String || p.GetType() == ParameterType::DoubleVector;
  if (!(line.empty() && emptyAllowed))
  {
    try
    {
      CheckValue(p, line);
    }
    catch (const InputError& e)
    {
      throw std::logic_error(std::string("return value ") + e.what());
    }
  }
  this->Values[name] = line;
}

void ReturnValues::Set(const std::string& name, double value)
{
  this->Set(name, FormatNumber(value));
}

void ReturnValues::Set(const std::string& name, int value)
{
  this->Set(name, std::to_string(value));
}

void ReturnValues::Set(const std::string& name, bool value)
{
  this->Set(name, std::string(value ? "true" : "false"));
}

void ReturnValues::Set(const std::string& name, const std::vector<double>& values)
{
  std::string text;
  for (double v : values)
  {
    text += (text.empty() ? "" : ",") + FormatNumber(v);
  }
  this->Set(name, text);
}

std::string ReturnValues::Text() const
{
  std::string text;
  for (const auto& group : this->Description->Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (p.IsReturnParameter())
      {
        const auto it = this->Values.find(p.GetName());
        text += p.GetName() + " = " + (it == this->Values.end() ? p.GetDefault() : it->second) + "\n";
      }
    }
  }
  return text;
}

void ReturnValues::Write(const std::string& fileName) const
{
  WriteFileAtomically(fileName, this->Text());
}

//----------------------------------------------------------------------------
namespace
{
/// --xml, --help or --version anywhere on the line: answered, and nothing else is done.
bool AnswerBuiltInFlag(const ModuleDescription& description, const std::vector<std::string>& args)
{
  if (std::find(args.begin(), args.end(), "--xml") != args.end())
  {
    std::cout << WriteXml(description);
    return true;
  }
  for (const auto& arg : args)
  {
    if (arg == "--help" || arg == "-h")
    {
      std::cout << WriteHelp(description);
      return true;
    }
    if (arg == "--version")
    {
      std::cout << description.Program << " " << description.Version << "\n";
      return true;
    }
  }
  return false;
}

} // namespace

int ReportFailure(const ModuleDescription& description, const std::string& who)
{
  try
  {
    throw;
  }
  catch (const UsageError& e)
  {
    std::cerr << who << ": error: " << e.what() << "\n";
    return 2;
  }
  catch (const ParameterError& e)
  {
    std::cerr << who << ": error: " << DisplayNameOfSetting(description, e.GetParameter()) << ": " << e.GetProblem() << "\n";
    return 1;
  }
  catch (const InputError& e)
  {
    std::cerr << who << ": error: " << e.what() << "\n";
    return 1;
  }
  catch (const DeviceError& e)
  {
    std::cerr << who << ": error: "
              << (e.GetSetting().empty() ? std::string(e.what()) : e.Describe(DisplayNameOfSetting(description, e.GetSetting()))) << "\n";
    return 4;
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << who << ": error: out of memory\n";
    return 3;
  }
  catch (const std::exception& e)
  {
    std::cerr << who << ": internal error: " << e.what() << "\n";
    return 3;
  }
}

int FinishStandardOutput(const std::string& who, int code)
{
  errno = 0;
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (!failed)
  {
    return code;
  }
  std::cerr << who << ": error: standard output: cannot write (" << std::strerror(errno != 0 ? errno : EIO) << ")\n";
  return code == 0 ? 1 : code;
}

int RunProgram(const ModuleDescription& description, int argc, const char* const* argv, const ProgramBody& body)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  try
  {
    ValidateDescription(description);
    if (AnswerBuiltInFlag(description, args))
    {
      return 0;
    }
    const ParsedArguments parsed = ParseArguments(description, args);
    ReturnValues results(description);
    {
      const StreamRedirect progressToStdout(std::cerr, std::cout.rdbuf());
      body(parsed, results);
    }
    if (!parsed.GetReturnParameterFile().empty())
    {
      results.Write(parsed.GetReturnParameterFile());
    }
    std::cout << results.Text();
    return FinishStandardOutput(description.Program, 0);
  }
  catch (...)
  {
    return ReportFailure(description, description.Program);
  }
}
} // namespace cli
} // namespace vp
