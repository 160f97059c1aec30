#ifndef vpInputError_h
#define vpInputError_h

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

namespace vp
{
/// An input the user gave us is not what it claims to be. The message is one line that names the
/// file (or the argument) and the problem, ready to be printed as it is.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& message)
    : std::runtime_error(message)
  {
  }
  InputError(const std::string& source, const std::string& problem)
    : std::runtime_error(source + ": " + problem)
  {
  }
};

/// No usable Vulkan device, or the device failed. The message is one line that says what is
/// missing, ready to be printed as it is.
class DeviceError : public std::runtime_error
{
public:
  explicit DeviceError(const std::string& message)
    : std::runtime_error(message)
  {
  }
  /// A device setting that chose none: the message names the setting as the logic knows it
  /// ("DeviceSelector") between before and after; a front end names it its own way (Describe).
  DeviceError(const std::string& setting, const std::string& before, const std::string& after)
    : std::runtime_error(before + setting + after)
    , Setting(setting)
    , Before(before)
    , After(after)
  {
  }
  /// The setting's name in the message, empty when no setting is to blame.
  const std::string& GetSetting() const { return this->Setting; }
  /// The message with the setting called displayName (what() when no setting is to blame).
  std::string Describe(const std::string& displayName) const
  {
    return this->Setting.empty() ? std::string(this->what()) : this->Before + displayName + this->After;
  }

private:
  std::string Setting;
  std::string Before;
  std::string After;
};

/// A setting of the logic outside what it accepts. The logic names the setting as it knows it
/// ("RangeMm", the name of its Set/Get pair), never as a front end spells it: a command reports
/// it under its flag (--range), a Slicer CLI under its XML name (rangeMm). what() reads
/// "RangeMm: problem" for a caller that has no names of its own.
class ParameterError : public InputError
{
public:
  ParameterError(const std::string& parameter, const std::string& problem)
    : InputError(parameter, problem)
    , Parameter(parameter)
    , Problem(problem)
  {
  }
  const std::string& GetParameter() const { return this->Parameter; }
  const std::string& GetProblem() const { return this->Problem; }

private:
  std::string Parameter;
  std::string Problem;
};

/// Text from an input as a one-line message may quote it: control characters (a line break in a
/// name) written as \n, \t, \xNN, and at most 80 characters of it.
inline std::string Printable(const std::string& text)
{
  std::string out;
  for (const char c : text)
  {
    if (out.size() >= 80)
    {
      out += "...";
      break;
    }
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
    {
      out += "\\n";
    }
    else if (c == '\t')
    {
      out += "\\t";
    }
    else if (u < 32 || u == 127)
    {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02X", u);
      out += hex;
    }
    else
    {
      out.push_back(c);
    }
  }
  return out;
}

/// A number as a message shows it: the shortest form to the given significant digits ("0.9",
/// "1.41421"), not std::to_string's fixed six decimals.
inline std::string NumberText(double value, int significantDigits = 6)
{
  std::ostringstream out;
  out.precision(significantDigits);
  out << value;
  return out.str();
}

/// A number in a report's fixed form, as printf's format writes it ("%.4f": columns of
/// frames.csv, "%.3f": a table on the terminal).
inline std::string FixedText(double value, const char* printfFormat)
{
  char text[64];
  std::snprintf(text, sizeof(text), printfFormat, value);
  return text;
}
} // namespace vp

#endif
