#ifndef vpCliDescription_h
#define vpCliDescription_h

// The command-line contract of a program, declared once: a Slicer CLI module (SlicerExecutionModel,
// "SEM") or a subcommand of vesselproximity.
//
// A program lists its parameters in one ModuleDescription. Everything a caller sees is generated
// from that table: the SEM XML printed on --xml (what 3D Slicer reads to build the module's panel
// and its command line; Slicer CLIs only), the --help text, the argument parser, and the
// return-parameter file. So the XML and the help declare exactly the arguments the program
// accepts, and a parameter cannot be read without having been declared.
//
// How 3D Slicer calls an executable CLI module (vtkSlicerCLIModuleLogic), which the parser
// follows: `--returnparameterfile FILE` first when the module declares return parameters; then
// each flagged parameter as `--longflag VALUE` (or `-f VALUE` when it has only a flag): scalars
// and enumerations always, with their current value; strings, vectors, files and directories
// only when not empty; booleans as a bare `--longflag` when true, left out when false; points
// as `--longflag x,y,z` per point, in the declared coordinate system; images, models and other
// data as the path of a temporary file Slicer writes (inputs) or reads back (outputs). Index
// (positional) parameters come last, in index order. Return parameters (simple outputs without a
// flag or index) are written by the program to the return-parameter file as `name = value`.

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vp
{
namespace cli
{
/// The SEM parameter kinds this project uses, each written as its SEM tag.
enum class ParameterType
{
  Integer,           ///< <integer>
  Float,             ///< <float>
  Double,            ///< <double>
  Boolean,           ///< <boolean>: a switch, given without a value
  String,            ///< <string>
  StringEnumeration, ///< <string-enumeration>: one of Elements
  DoubleVector,      ///< <double-vector>: numbers separated by commas
  Point,             ///< <point>: x,y,z in CoordinateSystem
  File,              ///< <file>
  Directory,         ///< <directory>
  Image,             ///< <image type="...">: a volume file (Slicer writes .nrrd)
  Geometry,          ///< <geometry type="model">: a surface file
  Transform,         ///< <transform type="linear">: a transform file (Slicer writes ITK's .h5)
  Table,             ///< <table type="color"> (a colour table, .ctbl), or <table> (a table node, .csv/.tsv)
  PointFile,         ///< <pointfile>: a markups file of points in CoordinateSystem
};

/// SEM tag of a type ("string-enumeration").
const char* TagOf(ParameterType type);

enum class Channel
{
  None,
  Input,
  Output,
};

/// One row of a program's parameter table. Built with chained setters:
///   Parameter(ParameterType::Float, "smoothing").SetLongFlag("smoothing").SetLabel("Smoothing")
///     .SetDescription("...").SetDefault("0.5").SetRange(0, 1, 0.05)
class Parameter
{
public:
  Parameter(ParameterType type, std::string name);

  /// One letter, without the dash; Slicer passes "-f".
  Parameter& SetFlag(std::string flag);
  /// Without the dashes; Slicer passes "--longflag".
  Parameter& SetLongFlag(std::string longFlag);
  /// Position among the index (positional) arguments, from 0.
  Parameter& SetIndex(int index);
  Parameter& SetLabel(std::string label);
  Parameter& SetDescription(std::string description);
  Parameter& SetDefault(std::string value);
  Parameter& SetChannel(Channel channel);
  /// <constraints>: the value must lie in [minimum, maximum]; step is the GUI's increment.
  Parameter& SetRange(double minimum, double maximum, double step);
  /// <element>s of an enumeration.
  Parameter& SetElements(std::vector<std::string> elements);
  /// The type="..." attribute of an image or geometry ("label", "model").
  Parameter& SetTypeAttribute(std::string type);
  /// The fileExtensions="..." attribute (".json", ".stl,.vtk"): the first is the format Slicer
  /// writes an input in and expects an output in.
  Parameter& SetFileExtensions(std::string extensions);
  /// The coordinateSystem="..." attribute of a point or point file: "lps" or "ras".
  Parameter& SetCoordinateSystem(std::string system);
  /// Refused when absent (SEM has no such element: the description says so, and the program
  /// reports a missing one as a usage error).
  Parameter& SetRequired(bool required = true);
  /// The logic's name of the setting this parameter gives ("RangeMm"): a vp::ParameterError the
  /// logic raises for it is reported under this parameter's DisplayName().
  Parameter& SetLogicName(std::string name);
  /// How --help shows the value ("CLASS=FILE[,CLASS=FILE...]"); default: a word for the type.
  Parameter& SetPlaceholder(std::string text);
  /// The last index parameter takes every remaining argument (SEM's multiple="true").
  Parameter& SetMultiple(bool multiple = true);

  ParameterType GetType() const { return this->Type; }
  const std::string& GetName() const { return this->Name; }
  const std::string& GetFlag() const { return this->Flag; }
  const std::string& GetLongFlag() const { return this->LongFlag; }
  int GetIndex() const { return this->Index; }
  const std::string& GetLabel() const { return this->Label; }
  const std::string& GetDescription() const { return this->Description; }
  const std::string& GetDefault() const { return this->Default; }
  Channel GetChannel() const { return this->ParameterChannel; }
  bool HasRange() const { return this->HasConstraints; }
  double GetMinimum() const { return this->Minimum; }
  double GetMaximum() const { return this->Maximum; }
  double GetStep() const { return this->Step; }
  const std::vector<std::string>& GetElements() const { return this->Elements; }
  const std::string& GetTypeAttribute() const { return this->TypeAttribute; }
  const std::string& GetFileExtensions() const { return this->FileExtensions; }
  const std::string& GetCoordinateSystem() const { return this->CoordinateSystem; }
  bool IsRequired() const { return this->Required; }
  const std::string& GetLogicName() const { return this->LogicName; }
  const std::string& GetPlaceholder() const { return this->Placeholder; }
  bool IsMultiple() const { return this->Multiple; }

  /// A simple output (number, boolean, string, enumeration, vector) with no flag and no index:
  /// Slicer does not pass it; the program reports it through the return-parameter file.
  bool IsReturnParameter() const;
  /// How messages name the parameter: "--longflag", "-f", or an index parameter's placeholder
  /// ("INPUT") or name.
  std::string DisplayName() const;

private:
  ParameterType Type;
  std::string Name, Flag, LongFlag;
  int Index = -1;
  std::string Label, Description, Default;
  Channel ParameterChannel = Channel::None;
  bool HasConstraints = false;
  double Minimum = 0.0, Maximum = 0.0, Step = 0.0;
  std::vector<std::string> Elements;
  std::string TypeAttribute, FileExtensions, CoordinateSystem, LogicName, Placeholder;
  bool Required = false;
  bool Multiple = false;
};

/// A <parameters> group: one collapsible section of the module's panel in Slicer.
struct ParameterGroup
{
  std::string Label;
  std::string Description;
  std::vector<Parameter> Parameters;
};

/// Everything the program's --xml says: the module's metadata and its parameter table.
struct ModuleDescription
{
  /// Who calls the program. A Slicer CLI follows SEM's rules (identifier longflags, a default for
  /// every number, switch and enumeration) and prints --xml. A subcommand of vesselproximity takes
  /// the same table and parser, and may also have dashed longflags and options with no default.
  enum class Kind
  {
    SlicerCli,
    Subcommand,
  };
  Kind Interface = Kind::SlicerCli;
  std::string Program; ///< executable name ("vesselproximity track" for a subcommand), for messages and --help
  std::string Category;
  std::string Title;
  std::string Description;
  std::string Version;
  std::string DocumentationUrl;
  std::string License;
  std::string Contributor;
  std::string Acknowledgements;
  std::vector<ParameterGroup> Groups;

  /// The parameter of that name; std::logic_error when none is declared (a programming error).
  const Parameter& Find(const std::string& name) const;
  /// The index (positional) parameters, in index order.
  std::vector<const Parameter*> IndexParameters() const;

  /// One of this project's programs: category IGT, our documentation link, licence, contributor
  /// line and acknowledgement, the given groups.
  static ModuleDescription VesselProximity(
    std::string program, std::string title, std::string version, std::vector<ParameterGroup> groups);
  /// A subcommand of the vesselproximity program: its title is the line the program's --help lists.
  static ModuleDescription Subcommand(
    std::string program, std::string title, std::string description, std::vector<ParameterGroup> groups);
};

/// The acknowledgement of the method our programs carry (GenerateCLP-safe: no double quote,
/// backslash or line break).
std::string MethodAcknowledgement();
/// VP_DOCUMENTATION_URL when the build sets one, else a file:// link to the README installed
/// beside the program (share/doc/VesselProximity) or, in the build tree, the source tree's.
std::string DocumentationUrl();

/// Checks the table itself: names unique C identifiers, flags unique and not the built-in ones,
/// indices 0..n-1, every parameter reachable (a flag, a longflag or an index) unless it is a
/// return parameter, defaults of the declared type within their constraints, enumeration defaults
/// among the elements. Throws std::logic_error naming the parameter: a broken table is a bug,
/// caught by the first run of any test.
void ValidateDescription(const ModuleDescription& description);

/// How messages name the parameter that gives a logic setting (Parameter::SetLogicName): its
/// DisplayName(), each side of "A/B" mapped alone; the setting's own name when none gives it.
std::string DisplayNameOfSetting(const ModuleDescription& description, const std::string& setting);

/// The SEM XML document, element order as Slicer's own modules write it, text escaped.
std::string WriteXml(const ModuleDescription& description);

/// The --help text: usage line, every parameter with its flag, type, default and description,
/// and the return parameters.
std::string WriteHelp(const ModuleDescription& description);

/// Wrong use of the command line: an unknown flag, a missing value or required parameter, an
/// extra argument. Exit code 2.
class UsageError : public std::runtime_error
{
public:
  UsageError(const std::string& source, const std::string& problem)
    : std::runtime_error(source + ": " + problem)
  {
  }
};

/// The values of one command line, checked against the table. Every getter takes a declared
/// name (std::logic_error otherwise) and falls back on the declared default.
class ParsedArguments
{
public:
  /// Whether the command line gave the parameter (a default does not count).
  bool IsSet(const std::string& name) const;
  std::string GetString(const std::string& name) const;
  double GetNumber(const std::string& name) const;
  int GetInteger(const std::string& name) const;
  bool GetBoolean(const std::string& name) const;
  /// A vector or point parameter's numbers; empty when neither given nor defaulted.
  std::vector<double> GetNumbers(const std::string& name) const;
  std::array<double, 3> GetPoint(const std::string& name) const;
  /// Every value of a multiple index parameter, in order (one value, or none, for any other).
  std::vector<std::string> GetStrings(const std::string& name) const;
  /// The path after --returnparameterfile, empty when not given.
  const std::string& GetReturnParameterFile() const { return this->ReturnParameterFile; }

private:
  friend ParsedArguments ParseArguments(const ModuleDescription&, const std::vector<std::string>&);
  const Parameter& Declared(const std::string& name) const;
  const ModuleDescription* Description = nullptr;
  std::map<std::string, std::string> Values;
  std::map<std::string, std::vector<std::string>> Multiple;
  std::string ReturnParameterFile;
};

/// Parses a command line (without the program name) as Slicer builds it: "--longflag VALUE",
/// "--longflag=VALUE", "-f VALUE", bare "--longflag" for a boolean, index arguments in order
/// ("--" ends the flags), and --returnparameterfile FILE. Every value is checked against its
/// type, constraints and elements. Throws UsageError (unknown flag, flag given twice, missing
/// value, extra argument, missing required parameter) or vp::InputError (a value that is not
/// what its parameter takes), each naming the parameter. The description must outlive the result.
ParsedArguments ParseArguments(const ModuleDescription& description, const std::vector<std::string>& args);

/// The simple outputs of a run, written as the return-parameter file Slicer reads back.
class ReturnValues
{
public:
  explicit ReturnValues(const ModuleDescription& description);

  /// name must be a declared return parameter (std::logic_error otherwise). Numbers are written
  /// in their shortest exact form; vectors as "x,y,z"; booleans as true/false.
  void Set(const std::string& name, const std::string& value);
  void Set(const std::string& name, const char* value) { this->Set(name, std::string(value)); }
  void Set(const std::string& name, double value);
  void Set(const std::string& name, int value);
  void Set(const std::string& name, bool value);
  void Set(const std::string& name, const std::vector<double>& values);

  /// "name = value" per declared return parameter, in table order; one that was not set gets
  /// its declared default, so Slicer never shows the value of an earlier run.
  std::string Text() const;
  /// Writes Text() to fileName atomically; throws vp::InputError naming the file on failure.
  void Write(const std::string& fileName) const;

private:
  const ModuleDescription* Description;
  std::map<std::string, std::string> Values;
};

/// The text of a number as return values and messages write it: shortest exact form ("4",
/// "0.35", "-1").
std::string FormatNumber(double value);

/// The exception being handled (call it inside a catch), as one line on stderr, "WHO: error: ...",
/// and its exit code: 2 usage (UsageError), 1 bad input (vp::InputError; a
/// vp::ParameterError under the parameter that gives the setting, DisplayNameOfSetting), 4 no
/// usable Vulkan device (vp::DeviceError), 3 out of memory or an internal error.
int ReportFailure(const ModuleDescription& description, const std::string& who);

/// A run's exit code once what it printed has reached standard output: when stdout cannot take
/// it (a full disk, /dev/full, a closed pipe), one line on stderr ("WHO: error: standard output:
/// ...") and exit code 1 instead of a silent 0.
int FinishStandardOutput(const std::string& who, int code);

/// What a program does once its arguments are parsed: fill results, or throw.
using ProgramBody = std::function<void(const ParsedArguments& args, ReturnValues& results)>;

/// The whole life of a CLI program: --xml, --help, --version; parse; run the body; print the
/// return values to stdout and write them to the --returnparameterfile; map failures to one line
/// on stderr ("PROGRAM: error: ...") and the exit code: 0 success, 1 bad input (vp::InputError),
/// 2 usage (UsageError), 4 no Vulkan device, 3 internal error (ReportFailure).
/// While the body runs, std::cerr is routed to stdout: Slicer logs anything on a CLI's stderr as
/// an error, so progress and warnings belong on stdout and stderr carries only the error line.
int RunProgram(const ModuleDescription& description, int argc, const char* const* argv, const ProgramBody& body);
} // namespace cli
} // namespace vp

#endif
