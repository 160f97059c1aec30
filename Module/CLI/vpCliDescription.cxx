#include "vpCliDescription.h"

#include "vpInputError.h"
#include "vtkVesselMeshWriter.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <new>
#include <set>
#include <sstream>

namespace vp
{
namespace cli
{
namespace
{
// Flags the runner answers itself, and the one Slicer passes to shared-object modules: a table
// may not take them over.
const std::set<std::string> ReservedLongFlags = { "xml", "help", "version", "returnparameterfile",
  "processinformationaddress" };
const std::set<std::string> ReservedFlags = { "h" };

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
    type == ParameterType::Geometry;
}

bool ParseDouble(const std::string& text, double& value)
{
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
  {
    return false;
  }
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return *end == '\0' && std::isfinite(value);
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

/// Checks one value against its parameter; throws vp::InputError naming the parameter.
void CheckValue(const Parameter& p, const std::string& value)
{
  const std::string who = p.DisplayName();
  switch (p.GetType())
  {
    case ParameterType::Integer:
    {
      char* end = nullptr;
      const long v = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || std::isspace(static_cast<unsigned char>(value[0])) || *end != '\0' ||
        v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      {
        throw InputError(who, "expected a whole number, got '" + value + "'");
      }
      if (p.HasRange() && (v < p.GetMinimum() || v > p.GetMaximum()))
      {
        throw InputError(who,
          "must be between " + FormatNumber(p.GetMinimum()) + " and " + FormatNumber(p.GetMaximum()) + ", got " + value);
      }
      return;
    }
    case ParameterType::Float:
    case ParameterType::Double:
    {
      double v = 0.0;
      if (!ParseDouble(value, v))
      {
        throw InputError(who, "expected a number, got '" + value + "'");
      }
      if (p.HasRange() && (v < p.GetMinimum() || v > p.GetMaximum()))
      {
        throw InputError(who,
          "must be between " + FormatNumber(p.GetMinimum()) + " and " + FormatNumber(p.GetMaximum()) + ", got " + value);
      }
      return;
    }
    case ParameterType::Boolean:
      if (value != "true" && value != "false")
      {
        throw InputError(who, "expected true or false, got '" + value + "'");
      }
      return;
    case ParameterType::StringEnumeration:
      if (std::find(p.GetElements().begin(), p.GetElements().end(), value) == p.GetElements().end())
      {
        throw InputError(who, "must be one of " + JoinElements(p.GetElements(), ", ") + "; got '" + value + "'");
      }
      return;
    case ParameterType::DoubleVector:
    {
      std::vector<double> numbers;
      if (!ParseNumberList(value, numbers))
      {
        throw InputError(who, "expected finite numbers separated by commas, got '" + value + "'");
      }
      return;
    }
    case ParameterType::Point:
    {
      std::vector<double> numbers;
      if (!ParseNumberList(value, numbers) || numbers.size() != 3)
      {
        throw InputError(who, "expected a point x,y,z (three finite numbers), got '" + value + "'");
      }
      return;
    }
    case ParameterType::String:
      return;
    case ParameterType::File:
    case ParameterType::Directory:
    case ParameterType::Image:
    case ParameterType::Geometry:
      if (value.empty())
      {
        throw InputError(who, "needs a path, got an empty one");
      }
      return;
  }
}

std::string EscapeXml(const std::string& text)
{
  std::string out;
  out.reserve(text.size());
  for (char c : text)
  {
    switch (c)
    {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Long text as Slicer's own XML carries it, in CDATA; a "]]>" inside is split across two
/// sections, the only thing CDATA cannot hold.
std::string Cdata(const std::string& text)
{
  std::string body = text;
  for (std::size_t at = body.find("]]>"); at != std::string::npos; at = body.find("]]>", at + 15))
  {
    body.replace(at, 3, "]]]]><![CDATA[>");
  }
  return "<![CDATA[" + body + "]]>";
}

void WriteElement(std::ostream& out, const std::string& indent, const std::string& tag, const std::string& text)
{
  if (text.empty())
  {
    out << indent << "<" << tag << "/>\n";
  }
  else
  {
    out << indent << "<" << tag << ">" << EscapeXml(text) << "</" << tag << ">\n";
  }
}

void WriteCdataElement(std::ostream& out, const std::string& indent, const std::string& tag, const std::string& text)
{
  if (text.empty())
  {
    out << indent << "<" << tag << "/>\n";
  }
  else
  {
    out << indent << "<" << tag << ">" << Cdata(text) << "</" << tag << ">\n";
  }
}

/// How --help shows the value a flag takes.
std::string Placeholder(const Parameter& p)
{
  switch (p.GetType())
  {
    case ParameterType::Integer:
      return "N";
    case ParameterType::Float:
    case ParameterType::Double:
      return "NUMBER";
    case ParameterType::Boolean:
      return "";
    case ParameterType::String:
      return "TEXT";
    case ParameterType::StringEnumeration:
      return JoinElements(p.GetElements(), "|");
    case ParameterType::DoubleVector:
      return "X,Y,Z";
    case ParameterType::Point:
      return "X,Y,Z";
    case ParameterType::Directory:
      return "DIR";
    default:
      return "FILE";
  }
}

std::string TypeWords(const Parameter& p)
{
  std::string words = TagOf(p.GetType());
  if (!p.GetTypeAttribute().empty())
  {
    words += " (" + p.GetTypeAttribute() + ")";
  }
  if (!p.GetCoordinateSystem().empty())
  {
    std::string system = p.GetCoordinateSystem();
    std::transform(system.begin(), system.end(), system.begin(), [](char c) { return static_cast<char>(std::toupper(c)); });
    words += " in " + system;
  }
  if (!p.GetFileExtensions().empty())
  {
    words += " " + p.GetFileExtensions();
  }
  return words;
}

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

const char* TagOf(ParameterType type)
{
  switch (type)
  {
    case ParameterType::Integer:
      return "integer";
    case ParameterType::Float:
      return "float";
    case ParameterType::Double:
      return "double";
    case ParameterType::Boolean:
      return "boolean";
    case ParameterType::String:
      return "string";
    case ParameterType::StringEnumeration:
      return "string-enumeration";
    case ParameterType::DoubleVector:
      return "double-vector";
    case ParameterType::Point:
      return "point";
    case ParameterType::File:
      return "file";
    case ParameterType::Directory:
      return "directory";
    case ParameterType::Image:
      return "image";
    case ParameterType::Geometry:
      return "geometry";
  }
  return "string";
}

std::string FormatNumber(double value)
{
  char text[64];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, result.ptr);
}

//----------------------------------------------------------------------------
Parameter::Parameter(ParameterType type, std::string name)
  : Type(type)
  , Name(std::move(name))
{
}

Parameter& Parameter::SetFlag(std::string flag)
{
  this->Flag = std::move(flag);
  return *this;
}

Parameter& Parameter::SetLongFlag(std::string longFlag)
{
  this->LongFlag = std::move(longFlag);
  return *this;
}

Parameter& Parameter::SetLogicName(std::string name)
{
  this->LogicName = std::move(name);
  return *this;
}

Parameter& Parameter::SetIndex(int index)
{
  this->Index = index;
  return *this;
}

Parameter& Parameter::SetLabel(std::string label)
{
  this->Label = std::move(label);
  return *this;
}

Parameter& Parameter::SetDescription(std::string description)
{
  this->Description = std::move(description);
  return *this;
}

Parameter& Parameter::SetDefault(std::string value)
{
  this->Default = std::move(value);
  return *this;
}

Parameter& Parameter::SetChannel(Channel channel)
{
  this->ParameterChannel = channel;
  return *this;
}

Parameter& Parameter::SetRange(double minimum, double maximum, double step)
{
  this->HasConstraints = true;
  this->Minimum = minimum;
  this->Maximum = maximum;
  this->Step = step;
  return *this;
}

Parameter& Parameter::SetElements(std::vector<std::string> elements)
{
  this->Elements = std::move(elements);
  return *this;
}

Parameter& Parameter::SetTypeAttribute(std::string type)
{
  this->TypeAttribute = std::move(type);
  return *this;
}

Parameter& Parameter::SetFileExtensions(std::string extensions)
{
  this->FileExtensions = std::move(extensions);
  return *this;
}

Parameter& Parameter::SetCoordinateSystem(std::string system)
{
  this->CoordinateSystem = std::move(system);
  return *this;
}

Parameter& Parameter::SetRequired(bool required)
{
  this->Required = required;
  return *this;
}

bool Parameter::IsReturnParameter() const
{
  return this->ParameterChannel == Channel::Output && this->Flag.empty() && this->LongFlag.empty() &&
    this->Index < 0 && IsSimpleType(this->Type);
}

std::string Parameter::DisplayName() const
{
  if (!this->LongFlag.empty())
  {
    return "--" + this->LongFlag;
  }
  if (!this->Flag.empty())
  {
    return "-" + this->Flag;
  }
  return this->Name;
}

ModuleDescription ModuleDescription::VesselProximity(
  std::string program, std::string title, std::string version, std::vector<ParameterGroup> groups)
{
  ModuleDescription d;
  d.Program = std::move(program);
  d.Category = "IGT";
  d.Title = std::move(title);
  d.Version = std::move(version);
  d.Contributor = "VesselProximity developers";
  d.Groups = std::move(groups);
  return d;
}

const Parameter& ModuleDescription::Find(const std::string& name) const
{
  for (const auto& group : this->Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (p.GetName() == name)
      {
        return p;
      }
    }
  }
  throw std::logic_error(this->Program + ": no parameter named '" + name + "' is declared");
}

//----------------------------------------------------------------------------
void ValidateDescription(const ModuleDescription& description)
{
  auto fail = [&](const Parameter& p, const std::string& problem) {
    throw std::logic_error(description.Program + ": parameter table: " + p.GetName() + ": " + problem);
  };
  std::set<std::string> names, flags, longFlags;
  std::set<int> indices;
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (!IsIdentifier(p.GetName()) || !names.insert(p.GetName()).second)
      {
        fail(p, "the name must be a C identifier, used once");
      }
      if (p.GetLabel().empty() || p.GetDescription().empty())
      {
        fail(p, "needs a label and a description");
      }
      if (!p.GetFlag().empty() &&
        (p.GetFlag().size() != 1 || !std::isalpha(static_cast<unsigned char>(p.GetFlag()[0])) ||
          ReservedFlags.count(p.GetFlag()) || !flags.insert(p.GetFlag()).second))
      {
        fail(p, "the flag must be one letter, not h, used once");
      }
      if (!p.GetLongFlag().empty() &&
        (!IsIdentifier(p.GetLongFlag()) || ReservedLongFlags.count(p.GetLongFlag()) ||
          !longFlags.insert(p.GetLongFlag()).second))
      {
        fail(p, "the longflag must be an identifier, not a built-in one, used once");
      }
      const bool flagged = !p.GetFlag().empty() || !p.GetLongFlag().empty();
      if (p.GetIndex() >= 0)
      {
        if (flagged || !indices.insert(p.GetIndex()).second)
        {
          fail(p, "an index parameter has no flag, and each index is used once");
        }
      }
      if (p.GetChannel() == Channel::Output && IsSimpleType(p.GetType()) && (flagged || p.GetIndex() >= 0))
      {
        fail(p, "a simple output is a return parameter: no flag, no index");
      }
      if (!flagged && p.GetIndex() < 0 && !p.IsReturnParameter())
      {
        fail(p, "needs a flag, a longflag or an index (only return parameters have none)");
      }
      if (p.IsReturnParameter() && p.IsRequired())
      {
        fail(p, "a return parameter cannot be required");
      }
      if (IsData(p.GetType()) && p.GetChannel() == Channel::None)
      {
        fail(p, "files, folders, images and models need a channel (input or output)");
      }
      if (p.GetType() == ParameterType::Boolean && p.GetIndex() >= 0)
      {
        fail(p, "a boolean is a switch, it cannot be an index parameter");
      }
      if (p.GetType() == ParameterType::StringEnumeration && p.GetElements().empty())
      {
        fail(p, "an enumeration needs elements");
      }
      if ((IsNumeric(p.GetType()) || p.GetType() == ParameterType::StringEnumeration ||
            p.GetType() == ParameterType::Boolean) &&
        p.GetDefault().empty() && !p.IsRequired())
      {
        fail(p, "needs a default: Slicer always passes this type with a value");
      }
      if (p.HasRange() && (!IsNumeric(p.GetType()) || !(p.GetMinimum() <= p.GetMaximum())))
      {
        fail(p, "constraints are for numbers, minimum <= maximum");
      }
      if (p.GetType() == ParameterType::Point && p.GetCoordinateSystem() != "lps" && p.GetCoordinateSystem() != "ras")
      {
        fail(p, "a point needs coordinateSystem lps or ras");
      }
      if (!p.GetDefault().empty())
      {
        try
        {
          CheckValue(p, p.GetDefault());
        }
        catch (const InputError& e)
        {
          fail(p, std::string("bad default: ") + e.what());
        }
      }
    }
  }
  int expected = 0;
  for (int index : indices)
  {
    if (index != expected++)
    {
      throw std::logic_error(description.Program + ": parameter table: indices must run 0, 1, 2, ...");
    }
  }
}

//----------------------------------------------------------------------------
std::string WriteXml(const ModuleDescription& description)
{
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<executable>\n";
  WriteElement(out, "  ", "category", description.Category);
  WriteElement(out, "  ", "title", description.Title);
  WriteCdataElement(out, "  ", "description", description.Description);
  WriteElement(out, "  ", "version", description.Version);
  WriteElement(out, "  ", "documentation-url", description.DocumentationUrl);
  WriteElement(out, "  ", "license", description.License);
  WriteElement(out, "  ", "contributor", description.Contributor);
  WriteCdataElement(out, "  ", "acknowledgements", description.Acknowledgements);
  for (const auto& group : description.Groups)
  {
    out << "  <parameters>\n";
    WriteElement(out, "    ", "label", group.Label);
    WriteCdataElement(out, "    ", "description", group.Description);
    for (const auto& p : group.Parameters)
    {
      const std::string tag = TagOf(p.GetType());
      out << "    <" << tag;
      if (!p.GetTypeAttribute().empty())
      {
        out << " type=\"" << EscapeXml(p.GetTypeAttribute()) << "\"";
      }
      if (p.GetType() == ParameterType::Point)
      {
        out << " multiple=\"false\" coordinateSystem=\"" << EscapeXml(p.GetCoordinateSystem()) << "\"";
      }
      if (!p.GetFileExtensions().empty())
      {
        out << " fileExtensions=\"" << EscapeXml(p.GetFileExtensions()) << "\"";
      }
      out << ">\n";
      const std::string in = "      ";
      WriteElement(out, in, "name", p.GetName());
      if (!p.GetFlag().empty())
      {
        WriteElement(out, in, "flag", p.GetFlag());
      }
      if (!p.GetLongFlag().empty())
      {
        WriteElement(out, in, "longflag", p.GetLongFlag());
      }
      if (p.GetIndex() >= 0)
      {
        WriteElement(out, in, "index", std::to_string(p.GetIndex()));
      }
      WriteElement(out, in, "label", p.GetLabel());
      WriteCdataElement(out, in, "description", p.GetDescription());
      if (p.GetChannel() != Channel::None)
      {
        WriteElement(out, in, "channel", p.GetChannel() == Channel::Input ? "input" : "output");
      }
      if (!p.GetDefault().empty())
      {
        WriteElement(out, in, "default", p.GetDefault());
      }
      for (const auto& element : p.GetElements())
      {
        WriteElement(out, in, "element", element);
      }
      if (p.HasRange())
      {
        out << in << "<constraints>\n";
        WriteElement(out, in + "  ", "minimum", FormatNumber(p.GetMinimum()));
        WriteElement(out, in + "  ", "maximum", FormatNumber(p.GetMaximum()));
        WriteElement(out, in + "  ", "step", FormatNumber(p.GetStep()));
        out << in << "</constraints>\n";
      }
      out << "    </" << tag << ">\n";
    }
    out << "  </parameters>\n";
  }
  out << "</executable>\n";
  return out.str();
}

std::string WriteHelp(const ModuleDescription& description)
{
  std::vector<const Parameter*> indexed;
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (p.GetIndex() >= 0)
      {
        indexed.push_back(&p);
      }
    }
  }
  std::sort(indexed.begin(), indexed.end(), [](const Parameter* a, const Parameter* b) { return a->GetIndex() < b->GetIndex(); });

  std::ostringstream out;
  out << "usage: " << description.Program << " [options]";
  for (const Parameter* p : indexed)
  {
    out << " " << (p->IsRequired() ? p->GetName() : "[" + p->GetName() + "]");
  }
  out << "\n" << description.Title << " (3D Slicer CLI module, category " << description.Category << ", version "
      << description.Version << ")\n"
      << description.Description << "\n";
  bool anyReturn = false;
  for (const auto& group : description.Groups)
  {
    bool header = false;
    for (const auto& p : group.Parameters)
    {
      if (p.IsReturnParameter())
      {
        anyReturn = true;
        continue;
      }
      if (!header)
      {
        out << "\n" << group.Label << ":\n";
        header = true;
      }
      std::string head;
      if (p.GetIndex() >= 0)
      {
        head = p.GetName() + " (argument " + std::to_string(p.GetIndex() + 1) + ")";
      }
      else
      {
        head = !p.GetFlag().empty() ? "-" + p.GetFlag() : "";
        if (!p.GetLongFlag().empty())
        {
          head += (head.empty() ? "" : ", ") + std::string("--") + p.GetLongFlag();
        }
        const std::string value = Placeholder(p);
        head += value.empty() ? "" : " " + value;
        if (p.GetLongFlag() != p.GetName())
        {
          head += "  (" + p.GetName() + ")";
        }
      }
      out << "  " << head << "\n      " << p.GetLabel() << ": " << TypeWords(p);
      if (p.GetChannel() != Channel::None)
      {
        out << ", " << (p.GetChannel() == Channel::Input ? "input" : "output");
      }
      if (p.IsRequired())
      {
        out << ", required";
      }
      if (!p.GetDefault().empty())
      {
        out << ", default " << p.GetDefault();
      }
      if (p.HasRange())
      {
        out << ", " << FormatNumber(p.GetMinimum()) << " to " << FormatNumber(p.GetMaximum());
      }
      out << ".\n      " << p.GetDescription() << "\n";
    }
  }
  if (anyReturn)
  {
    out << "\nReturn parameters (printed as name = value, and written to --returnparameterfile FILE):\n";
    for (const auto& group : description.Groups)
    {
      for (const auto& p : group.Parameters)
      {
        if (p.IsReturnParameter())
        {
          out << "  " << p.GetName() << "  (" << TagOf(p.GetType()) << ", default "
              << (p.GetDefault().empty() ? "empty" : p.GetDefault()) << ")\n      " << p.GetLabel() << ": "
              << p.GetDescription() << "\n";
        }
      }
    }
  }
  out << "\nAlso: --xml (the SlicerExecutionModel description), --help, --version, --returnparameterfile FILE.\n"
         "Exit codes: 0 success, 1 bad input (one line on stderr names the parameter or file), 2 bad usage,\n"
         "3 internal error.\n";
  return out.str();
}

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

ParsedArguments ParseArguments(const ModuleDescription& description, const std::vector<std::string>& args)
{
  ParsedArguments parsed;
  parsed.Description = &description;
  std::map<std::string, const Parameter*> byFlag;
  std::vector<const Parameter*> indexed;
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (!p.GetFlag().empty())
      {
        byFlag["-" + p.GetFlag()] = &p;
      }
      if (!p.GetLongFlag().empty())
      {
        byFlag["--" + p.GetLongFlag()] = &p;
      }
      if (p.GetIndex() >= 0)
      {
        indexed.push_back(&p);
      }
    }
  }
  std::sort(indexed.begin(), indexed.end(), [](const Parameter* a, const Parameter* b) { return a->GetIndex() < b->GetIndex(); });

  std::vector<std::string> positionals;
  bool optionsEnded = false;
  bool returnFileGiven = false;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (optionsEnded || arg.size() < 2 || arg[0] != '-')
    {
      positionals.push_back(arg);
      continue;
    }
    if (arg == "--")
    {
      optionsEnded = true;
      continue;
    }
    std::string key = arg, value;
    bool inlineValue = false;
    const std::size_t eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos)
    {
      key = arg.substr(0, eq);
      value = arg.substr(eq + 1);
      inlineValue = true;
    }
    auto takeValue = [&]() {
      if (!inlineValue)
      {
        if (i + 1 >= args.size())
        {
          throw UsageError(key, "needs a value");
        }
        value = args[++i];
      }
    };
    if (key == "--returnparameterfile")
    {
      takeValue();
      if (returnFileGiven || value.empty())
      {
        throw UsageError(key, "give one file, once");
      }
      returnFileGiven = true;
      parsed.ReturnParameterFile = value;
      continue;
    }
    const auto found = byFlag.find(key);
    if (found == byFlag.end())
    {
      throw UsageError(key, "unknown parameter (see " + description.Program + " --help)");
    }
    const Parameter& p = *found->second;
    if (p.GetType() == ParameterType::Boolean)
    {
      if (inlineValue)
      {
        throw UsageError(key, "is a switch and takes no value: give it for true, leave it out for false");
      }
      value = "true";
    }
    else
    {
      takeValue();
    }
    if (parsed.Values.count(p.GetName()))
    {
      throw UsageError(key, "given twice");
    }
    CheckValue(p, value);
    parsed.Values[p.GetName()] = value;
  }
  if (positionals.size() > indexed.size())
  {
    throw UsageError(positionals[indexed.size()],
      "unexpected argument (" + description.Program + " takes " + std::to_string(indexed.size()) +
        " without a flag; see --help)");
  }
  for (std::size_t k = 0; k < positionals.size(); ++k)
  {
    CheckValue(*indexed[k], positionals[k]);
    parsed.Values[indexed[k]->GetName()] = positionals[k];
  }
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (p.IsRequired() && !parsed.Values.count(p.GetName()))
      {
        throw UsageError(p.DisplayName(), "is required (" + p.GetLabel() + ")");
      }
    }
  }
  return parsed;
}

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
int RunProgram(const ModuleDescription& description, int argc, const char* const* argv, const ProgramBody& body)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  const std::string& program = description.Program;
  try
  {
    ValidateDescription(description);
    for (const auto& arg : args)
    {
      if (arg == "--xml")
      {
        std::cout << WriteXml(description);
        return 0;
      }
    }
    for (const auto& arg : args)
    {
      if (arg == "--help" || arg == "-h")
      {
        std::cout << WriteHelp(description);
        return 0;
      }
      if (arg == "--version")
      {
        std::cout << program << " " << description.Version << "\n";
        return 0;
      }
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
    std::cout << results.Text() << std::flush;
    return 0;
  }
  catch (const UsageError& e)
  {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  }
  catch (const ExitError& e)
  {
    std::cerr << program << ": error: " << e.what() << "\n";
    return e.GetExitCode();
  }
  catch (const ParameterError& e)
  {
    std::string name = e.GetParameter();
    for (const ParameterGroup& group : description.Groups)
    {
      for (const Parameter& p : group.Parameters)
      {
        name = p.GetLogicName() == e.GetParameter() ? p.DisplayName() : name;
      }
    }
    std::cerr << program << ": error: " << name << ": " << e.GetProblem() << "\n";
    return 1;
  }
  catch (const InputError& e)
  {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 1;
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << program << ": error: out of memory\n";
    return 3;
  }
  catch (const std::exception& e)
  {
    std::cerr << program << ": internal error: " << e.what() << "\n";
    return 3;
  }
}
} // namespace cli
} // namespace vp
