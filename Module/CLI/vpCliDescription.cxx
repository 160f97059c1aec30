// The parameter table of a program: its rows and the check of the table itself.
#include "vpCliDescription.h"
#include "vpCliValues.h"

#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

namespace vp
{
namespace cli
{
namespace
{
namespace fs = std::filesystem;
// Flags the runner answers itself, and the one Slicer passes to shared-object modules: a table
// may not take them over.
const std::set<std::string> ReservedLongFlags = { "xml", "help", "version", "returnparameterfile",
  "processinformationaddress" };
const std::set<std::string> ReservedFlags = { "h" };
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
    case ParameterType::Transform:
      return "transform";
    case ParameterType::Table:
      return "table";
    case ParameterType::PointFile:
      return "pointfile";
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

Parameter& Parameter::SetPlaceholder(std::string text)
{
  this->Placeholder = std::move(text);
  return *this;
}

Parameter& Parameter::SetMultiple(bool multiple)
{
  this->Multiple = multiple;
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
  return this->Index >= 0 && !this->Placeholder.empty() ? this->Placeholder : this->Name;
}

ModuleDescription ModuleDescription::VesselProximity(
  std::string program, std::string title, std::string version, std::vector<ParameterGroup> groups)
{
  ModuleDescription d;
  d.Program = std::move(program);
  d.Category = "IGT";
  d.Title = std::move(title);
  d.Version = std::move(version);
  d.DocumentationUrl = cli::DocumentationUrl();
  d.License = "Apache-2.0";
  d.Contributor = "VesselProximity developers";
  d.Acknowledgements = MethodAcknowledgement();
  d.Groups = std::move(groups);
  return d;
}

std::string MethodAcknowledgement()
{
  // No double quote, backslash or line break: GenerateCLP pastes this text raw into a C string.
  return "Implements and extends the method of Noborio et al., 'Comparison of GPU-based and CPU-based "
         "Algorithms for Determining the Minimum Distance between a CUSA Scalpel and Blood Vessels'. Surface "
         "generation follows 3D Slicer's labelmap-to-closed-surface conversion.";
}

std::string DocumentationUrl()
{
#ifdef VP_DOCUMENTATION_URL
  if (*VP_DOCUMENTATION_URL)
  {
    return VP_DOCUMENTATION_URL;
  }
#endif
  // The README beside an installed tree (the CLI in lib/Slicer-X.Y/cli-modules, the README in
  // share/doc/VesselProximity), else the source tree's when run from the build tree: a clinical
  // workstation is often offline, and a link that works there beats a web page it cannot reach.
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> candidates;
  if (!ec)
  {
    candidates.push_back(program.parent_path() / "../../../share/doc/VesselProximity/README.md");
  }
#ifdef VP_SOURCE_README
  candidates.push_back(VP_SOURCE_README);
#endif
  for (const fs::path& readme : candidates)
  {
    if (fs::is_regular_file(readme, ec))
    {
      return "file://" + fs::weakly_canonical(readme, ec).string();
    }
  }
  return std::string();
}

ModuleDescription ModuleDescription::Subcommand(
  std::string program, std::string title, std::string description, std::vector<ParameterGroup> groups)
{
  ModuleDescription d;
  d.Interface = Kind::Subcommand;
  d.Program = std::move(program);
  d.Title = std::move(title);
  d.Description = std::move(description);
  d.Groups = std::move(groups);
  return d;
}

std::vector<const Parameter*> ModuleDescription::IndexParameters() const
{
  std::vector<const Parameter*> indexed;
  for (const auto& group : this->Groups)
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
  return indexed;
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
namespace
{
[[noreturn]] void Fail(const ModuleDescription& description, const Parameter& p, const std::string& problem)
{
  throw std::logic_error(description.Program + ": parameter table: " + p.GetName() + ": " + problem);
}

/// A Slicer longflag is an identifier; a subcommand's may also join lower-case words with dashes
/// ("frame-budget-ms"), as command-line programs write them.
bool IsLongFlag(const std::string& text, ModuleDescription::Kind kind)
{
  if (kind == ModuleDescription::Kind::SlicerCli || text.find('-') == std::string::npos)
  {
    return IsIdentifier(text);
  }
  return std::islower(static_cast<unsigned char>(text[0])) && text.back() != '-' && text.find("--") == std::string::npos &&
    std::all_of(text.begin(), text.end(),
      [](char c) { return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '-'; });
}

/// What the whole table must hold once: names, flags, longflags and indices.
struct TableNames
{
  std::set<std::string> Names, Flags, LongFlags;
  std::set<int> Indices;
};

/// The parameter's name, label, flags and index: present where needed, each used once.
void CheckNaming(const ModuleDescription& description, const Parameter& p, TableNames& seen)
{
  const bool slicer = description.Interface == ModuleDescription::Kind::SlicerCli;
  if (!IsIdentifier(p.GetName()) || !seen.Names.insert(p.GetName()).second)
  {
    Fail(description, p, "the name must be a C identifier, used once");
  }
  if ((slicer && p.GetLabel().empty()) || p.GetDescription().empty())
  {
    Fail(description, p, slicer ? "needs a label and a description" : "needs a description");
  }
  if (!p.GetFlag().empty() &&
    (p.GetFlag().size() != 1 || !std::isalpha(static_cast<unsigned char>(p.GetFlag()[0])) ||
      ReservedFlags.count(p.GetFlag()) || !seen.Flags.insert(p.GetFlag()).second))
  {
    Fail(description, p, "the flag must be one letter, not h, used once");
  }
  if (!p.GetLongFlag().empty() &&
    (!IsLongFlag(p.GetLongFlag(), description.Interface) || ReservedLongFlags.count(p.GetLongFlag()) ||
      !seen.LongFlags.insert(p.GetLongFlag()).second))
  {
    Fail(description, p, "the longflag must be an identifier, not a built-in one, used once");
  }
  const bool flagged = !p.GetFlag().empty() || !p.GetLongFlag().empty();
  if (p.GetIndex() >= 0 && (flagged || !seen.Indices.insert(p.GetIndex()).second))
  {
    Fail(description, p, "an index parameter has no flag, and each index is used once");
  }
  if (!flagged && p.GetIndex() < 0 && !p.IsReturnParameter())
  {
    Fail(description, p, "needs a flag, a longflag or an index (only return parameters have none)");
  }
  if (p.IsMultiple() && p.GetIndex() < 0)
  {
    Fail(description, p, "only an index parameter takes several values");
  }
}

/// The parameter's channel, type attributes and default agree with its type.
void CheckKind(const ModuleDescription& description, const Parameter& p)
{
  const bool flagged = !p.GetFlag().empty() || !p.GetLongFlag().empty();
  if (p.GetChannel() == Channel::Output && IsSimpleType(p.GetType()) && (flagged || p.GetIndex() >= 0))
  {
    Fail(description, p, "a simple output is a return parameter: no flag, no index");
  }
  if (p.IsReturnParameter() && p.IsRequired())
  {
    Fail(description, p, "a return parameter cannot be required");
  }
  if (IsData(p.GetType()) && p.GetChannel() == Channel::None)
  {
    Fail(description, p, "files, folders, images and models need a channel (input or output)");
  }
  if (p.GetType() == ParameterType::Boolean && p.GetIndex() >= 0)
  {
    Fail(description, p, "a boolean is a switch, it cannot be an index parameter");
  }
  if (p.GetType() == ParameterType::StringEnumeration && p.GetElements().empty())
  {
    Fail(description, p, "an enumeration needs elements");
  }
  // Slicer always passes these types with a value; a subcommand may leave one out.
  if (description.Interface == ModuleDescription::Kind::SlicerCli &&
    (IsNumeric(p.GetType()) || p.GetType() == ParameterType::StringEnumeration || p.GetType() == ParameterType::Boolean) &&
    p.GetDefault().empty() && !p.IsRequired())
  {
    Fail(description, p, "needs a default: Slicer always passes this type with a value");
  }
  if (p.HasRange() && (!IsNumeric(p.GetType()) || !(p.GetMinimum() <= p.GetMaximum())))
  {
    Fail(description, p, "constraints are for numbers, minimum <= maximum");
  }
  if ((p.GetType() == ParameterType::Point || p.GetType() == ParameterType::PointFile) &&
    p.GetCoordinateSystem() != "lps" && p.GetCoordinateSystem() != "ras")
  {
    Fail(description, p, "a point or point file needs coordinateSystem lps or ras");
  }
  // Slicer picks the node kind of these by their type attribute (SEM's parser refuses other types;
  // a table without one is a table node).
  const std::map<ParameterType, std::set<std::string>> types = { { ParameterType::Image, { "scalar", "label", "vector" } },
    { ParameterType::Geometry, { "model" } }, { ParameterType::Transform, { "linear" } },
    { ParameterType::Table, { "", "color" } } };
  const auto known = types.find(p.GetType());
  if (known != types.end() && !known->second.count(p.GetTypeAttribute()))
  {
    Fail(description, p, std::string("a ") + TagOf(p.GetType()) + " needs a type Slicer knows (" +
        JoinElements(std::vector<std::string>(known->second.begin(), known->second.end()), ", ") + ")");
  }
}

void CheckDefault(const ModuleDescription& description, const Parameter& p)
{
  if (p.GetDefault().empty())
  {
    return;
  }
  try
  {
    CheckValue(p, p.GetDefault());
  }
  catch (const InputError& e)
  {
    Fail(description, p, std::string("bad default: ") + e.what());
  }
}
} // namespace

void ValidateDescription(const ModuleDescription& description)
{
  if (description.Program.empty() || description.Title.empty())
  {
    throw std::logic_error("a program's description needs its name and a title");
  }
  TableNames seen;
  const Parameter* multiple = nullptr;
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      CheckNaming(description, p, seen);
      CheckKind(description, p);
      CheckDefault(description, p);
      multiple = p.IsMultiple() ? &p : multiple;
    }
  }
  int expected = 0;
  for (int index : seen.Indices)
  {
    if (index != expected++)
    {
      throw std::logic_error(description.Program + ": parameter table: indices must run 0, 1, 2, ...");
    }
  }
  if (multiple && multiple->GetIndex() != expected - 1)
  {
    Fail(description, *multiple, "only the last index parameter takes several values");
  }
}

std::string DisplayNameOfSetting(const ModuleDescription& description, const std::string& setting)
{
  const std::size_t slash = setting.find('/');
  if (slash != std::string::npos) // two settings that refuse together ("CellSizeMm/ResolutionPx")
  {
    return DisplayNameOfSetting(description, setting.substr(0, slash)) + "/" +
      DisplayNameOfSetting(description, setting.substr(slash + 1));
  }
  for (const ParameterGroup& group : description.Groups)
  {
    for (const Parameter& p : group.Parameters)
    {
      if (p.GetLogicName() == setting)
      {
        return p.DisplayName();
      }
    }
  }
  return setting;
}

} // namespace cli
} // namespace vp
