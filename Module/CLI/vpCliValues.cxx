// Values of the parameter kinds: how a command line's text is read and checked.
#include "vpCliValues.h"

#include "vpDecimal.h"
#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace vp
{
namespace cli
{
bool IsIdentifier(const std::string& text)
{
  if (text.empty() || !(std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_'))
  {
    return false;
  }
  return std::all_of(text.begin(), text.end(),
    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

bool IsSimpleType(ParameterType type)
{
  switch (type)
  {
    case ParameterType::Integer:
    case ParameterType::Float:
    case ParameterType::Double:
    case ParameterType::Boolean:
    case ParameterType::String:
    case ParameterType::StringEnumeration:
    case ParameterType::DoubleVector:
      return true;
    default:
      return false;
  }
}

bool IsNumeric(ParameterType type)
{
  return type == ParameterType::Integer || type == ParameterType::Float || type == ParameterType::Double;
}

/// Whether the type names a file or folder, which SEM ties to a channel.
bool IsData(ParameterType type)
{
  return type == ParameterType::File || type == ParameterType::Directory || type == ParameterType::Image ||
    type == ParameterType::Geometry || type == ParameterType::Transform || type == ParameterType::Table ||
    type == ParameterType::PointFile;
}

bool ParseDouble(const std::string& text, double& value)
{
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
  {
    return false;
  }
  // A plain decimal only: strtod would also read "0x10" as 16, which nobody means as a setting.
  value = std::strtod(text.c_str(), nullptr);
  return *ScanDecimal(text.c_str()) == '\0' && std::isfinite(value);
}

/// Numbers separated by commas and/or blanks ("1,2,3", "1 2 3"), as Slicer and people write them.
bool ParseNumberList(const std::string& text, std::vector<double>& numbers)
{
  numbers.clear();
  std::string token;
  auto flush = [&]() {
    if (token.empty())
    {
      return true;
    }
    double v = 0.0;
    if (!ParseDouble(token, v))
    {
      return false;
    }
    numbers.push_back(v);
    token.clear();
    return true;
  };
  bool expectNumber = true; // a comma with nothing before it is a missing number
  for (char c : text)
  {
    if (c == ',')
    {
      if (expectNumber && token.empty())
      {
        return false;
      }
      if (!flush())
      {
        return false;
      }
      expectNumber = true;
    }
    else if (std::isspace(static_cast<unsigned char>(c)))
    {
      if (!flush())
      {
        return false;
      }
    }
    else
    {
      token += c;
      expectNumber = false;
    }
  }
  return flush() && !expectNumber && !numbers.empty();
}

std::string JoinElements(const std::vector<std::string>& elements, const char* separator)
{
  std::string text;
  for (const auto& e : elements)
  {
    text += (text.empty() ? "" : separator) + e;
  }
  return text;
}

namespace
{
void CheckRange(const Parameter& p, double v, const std::string& value)
{
  if (p.HasRange() && (v < p.GetMinimum() || v > p.GetMaximum()))
  {
    throw InputError(p.DisplayName(),
      "must be between " + FormatNumber(p.GetMinimum()) + " and " + FormatNumber(p.GetMaximum()) + ", got " + value);
  }
}

void CheckInteger(const Parameter& p, const std::string& value)
{
  char* end = nullptr;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || std::isspace(static_cast<unsigned char>(value[0])) || *end != '\0' ||
    v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
  {
    throw InputError(p.DisplayName(), "expected a whole number, got '" + value + "'");
  }
  CheckRange(p, static_cast<double>(v), value);
}

void CheckReal(const Parameter& p, const std::string& value)
{
  double v = 0.0;
  if (!ParseDouble(value, v))
  {
    throw InputError(p.DisplayName(), "expected a number, got '" + value + "'");
  }
  CheckRange(p, v, value);
}

void CheckNumbers(const Parameter& p, const std::string& value)
{
  std::vector<double> numbers;
  if (p.GetType() == ParameterType::DoubleVector && !ParseNumberList(value, numbers))
  {
    throw InputError(p.DisplayName(), "expected finite numbers separated by commas, got '" + value + "'");
  }
  if (p.GetType() == ParameterType::Point && (!ParseNumberList(value, numbers) || numbers.size() != 3))
  {
    throw InputError(p.DisplayName(), "expected a point x,y,z (three finite numbers), got '" + value + "'");
  }
}
} // namespace

void CheckValue(const Parameter& p, const std::string& value)
{
  switch (p.GetType())
  {
    case ParameterType::Integer:
      return CheckInteger(p, value);
    case ParameterType::Float:
    case ParameterType::Double:
      return CheckReal(p, value);
    case ParameterType::Boolean:
      if (value != "true" && value != "false")
      {
        throw InputError(p.DisplayName(), "expected true or false, got '" + value + "'");
      }
      return;
    case ParameterType::StringEnumeration:
      if (std::find(p.GetElements().begin(), p.GetElements().end(), value) == p.GetElements().end())
      {
        throw InputError(p.DisplayName(), "must be one of " + JoinElements(p.GetElements(), ", ") + "; got '" + value + "'");
      }
      return;
    case ParameterType::DoubleVector:
    case ParameterType::Point:
      return CheckNumbers(p, value);
    case ParameterType::String:
      return;
    case ParameterType::File:
    case ParameterType::Directory:
    case ParameterType::Image:
    case ParameterType::Geometry:
    case ParameterType::Transform:
    case ParameterType::Table:
    case ParameterType::PointFile:
      if (value.empty())
      {
        throw InputError(p.DisplayName(), "needs a path, got an empty one");
      }
      return;
  }
}
} // namespace cli
} // namespace vp
