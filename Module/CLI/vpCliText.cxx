// What a description says to people and to Slicer: the --help text and the SEM XML.
#include "vpCliDescription.h"
#include "vpCliValues.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace vp
{
namespace cli
{
namespace
{
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
  if (!p.GetPlaceholder().empty())
  {
    return p.GetPlaceholder();
  }
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

/// The opening tag of a parameter with its attributes: <point multiple="false" coordinateSystem="lps">.
void WriteParameterTag(std::ostream& out, const Parameter& p)
{
  out << "    <" << TagOf(p.GetType());
  if (!p.GetTypeAttribute().empty())
  {
    out << " type=\"" << EscapeXml(p.GetTypeAttribute()) << "\"";
  }
  if (p.IsMultiple())
  {
    out << " multiple=\"true\"";
  }
  else if (p.GetType() == ParameterType::Point || p.GetType() == ParameterType::PointFile)
  {
    out << " multiple=\"false\"";
  }
  if (p.GetType() == ParameterType::Point || p.GetType() == ParameterType::PointFile)
  {
    out << " coordinateSystem=\"" << EscapeXml(p.GetCoordinateSystem()) << "\"";
  }
  if (!p.GetFileExtensions().empty())
  {
    out << " fileExtensions=\"" << EscapeXml(p.GetFileExtensions()) << "\"";
  }
  out << ">\n";
}

void WriteParameterXml(std::ostream& out, const Parameter& p)
{
  WriteParameterTag(out, p);
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
  out << "    </" << TagOf(p.GetType()) << ">\n";
}
} // namespace

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
      WriteParameterXml(out, p);
    }
    out << "  </parameters>\n";
  }
  out << "</executable>\n";
  return out.str();
}

//----------------------------------------------------------------------------
namespace
{
/// Text wrapped at 96 columns under an indent; a line that starts with a blank is kept as written
/// (a table, a list of keys).
std::string Wrap(const std::string& text, const std::string& indent)
{
  std::string out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
  {
    if (!line.empty() && line[0] == ' ')
    {
      out += indent + line + "\n";
      continue;
    }
    std::istringstream words(line);
    std::string row;
    for (std::string word; words >> word;)
    {
      if (!row.empty() && indent.size() + row.size() + 1 + word.size() > 96)
      {
        out += indent + row + "\n";
        row.clear();
      }
      row += (row.empty() ? "" : " ") + word;
    }
    out += indent + row + "\n";
  }
  return out;
}

/// "-o, --output DIR", or an index parameter's name.
std::string FlagHead(const Parameter& p)
{
  if (p.GetIndex() >= 0)
  {
    return p.GetPlaceholder().empty() ? p.GetName() : p.GetPlaceholder();
  }
  std::string head = !p.GetFlag().empty() ? "-" + p.GetFlag() : "";
  if (!p.GetLongFlag().empty())
  {
    head += (head.empty() ? "" : ", ") + std::string("--") + p.GetLongFlag();
  }
  const std::string value = Placeholder(p);
  return head + (value.empty() ? "" : " " + value);
}

/// A Slicer parameter: its flags and name, label, SEM type, channel, default and range, description.
void WriteSlicerParameterHelp(std::ostream& out, const Parameter& p)
{
  std::string head = p.GetIndex() >= 0 ? p.GetName() + " (argument " + std::to_string(p.GetIndex() + 1) + ")" : FlagHead(p);
  head += p.GetIndex() < 0 && p.GetLongFlag() != p.GetName() ? "  (" + p.GetName() + ")" : "";
  out << "  " << head << "\n      " << p.GetLabel() << ": " << TypeWords(p);
  if (p.GetChannel() != Channel::None)
  {
    out << ", " << (p.GetChannel() == Channel::Input ? "input" : "output");
  }
  out << (p.IsRequired() ? ", required" : "") << (p.GetDefault().empty() ? "" : ", default " + p.GetDefault());
  if (p.HasRange())
  {
    out << ", " << FormatNumber(p.GetMinimum()) << " to " << FormatNumber(p.GetMaximum());
  }
  out << ".\n      " << p.GetDescription() << "\n";
}

/// A subcommand's option: its flags and value, then what it does, wrapped, with its default.
void WriteSubcommandParameterHelp(std::ostream& out, const Parameter& p)
{
  std::string text = p.GetDescription();
  text += p.IsRequired() ? " Required." : "";
  if (!p.GetDefault().empty() && p.GetType() != ParameterType::Boolean)
  {
    text += " Default: " + p.GetDefault() + ".";
  }
  if (p.HasRange())
  {
    text += " From " + FormatNumber(p.GetMinimum()) + " to " + FormatNumber(p.GetMaximum()) + ".";
  }
  out << "  " << FlagHead(p) << "\n" << Wrap(text, "      ");
}

/// The index parameters as the usage line names them: "INPUT...", "[NAME]".
std::string IndexUsage(const ModuleDescription& description)
{
  std::string text;
  for (const Parameter* p : description.IndexParameters())
  {
    const std::string name = FlagHead(*p) + (p->IsMultiple() ? "..." : "");
    text += " " + (p->IsRequired() ? name : "[" + name + "]");
  }
  return text;
}

/// A Slicer CLI's usage names its index parameters after its options, as SEM's programs do:
/// "usage: PROGRAM [options] INDEX [OPTIONAL]". A subcommand's names what it is given first,
/// then the options it cannot run without: "usage: vesselproximity models INPUT... -o OUTDIR [options]".
std::string UsageLine(const ModuleDescription& description)
{
  if (description.Interface == ModuleDescription::Kind::SlicerCli)
  {
    return "usage: " + description.Program + " [options]" + IndexUsage(description) + "\n";
  }
  std::string line = "usage: " + description.Program + IndexUsage(description);
  bool optional = false;
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (p.GetIndex() < 0 && p.IsRequired())
      {
        const std::string value = Placeholder(p);
        line += " " + (p.GetFlag().empty() ? "--" + p.GetLongFlag() : "-" + p.GetFlag()) + (value.empty() ? "" : " " + value);
      }
      optional = optional || (p.GetIndex() < 0 && !p.IsRequired() && !p.IsReturnParameter());
    }
  }
  return line + (optional ? " [options]" : "") + "\n";
}

void WriteReturnParametersHelp(std::ostream& out, const ModuleDescription& description)
{
  bool header = false;
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      if (!p.IsReturnParameter())
      {
        continue;
      }
      if (!header)
      {
        out << "\nReturn parameters (printed as name = value, and written to --returnparameterfile FILE):\n";
        header = true;
      }
      out << "  " << p.GetName() << "  (" << TagOf(p.GetType()) << ", default "
          << (p.GetDefault().empty() ? "empty" : p.GetDefault()) << ")\n      " << p.GetLabel() << ": "
          << p.GetDescription() << "\n";
    }
  }
}
} // namespace

std::string WriteHelp(const ModuleDescription& description)
{
  const bool slicer = description.Interface == ModuleDescription::Kind::SlicerCli;
  std::ostringstream out;
  out << UsageLine(description);
  if (slicer)
  {
    out << description.Title << " (3D Slicer CLI module, category " << description.Category << ", version "
        << description.Version << ")\n"
        << description.Description << "\n";
  }
  else
  {
    std::string title = description.Title;
    title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
    out << Wrap(title + ".", "  ") << Wrap(description.Description, "  ");
  }
  for (const auto& group : description.Groups)
  {
    bool header = false;
    for (const auto& p : group.Parameters)
    {
      if (!p.IsReturnParameter())
      {
        out << (header ? "" : "\n" + group.Label + ":\n");
        header = true;
        slicer ? WriteSlicerParameterHelp(out, p) : WriteSubcommandParameterHelp(out, p);
      }
    }
  }
  WriteReturnParametersHelp(out, description);
  if (slicer)
  {
    out << "\nAlso: --xml (the SlicerExecutionModel description), --help, --version, --returnparameterfile FILE.\n"
           "Exit codes: 0 success, 1 bad input (one line on stderr names the parameter or file), 2 bad usage,\n"
           "3 internal error.\n";
  }
  else
  {
    out << "\nExit codes: 0 success, 1 bad input (one line on stderr names the option or file), 2 bad usage,\n"
           "3 internal error, 4 no usable Vulkan device (z-buffer engine).\n";
  }
  return out.str();
}
} // namespace cli
} // namespace vp
