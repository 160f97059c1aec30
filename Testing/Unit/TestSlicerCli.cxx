// The Slicer CLI entry points, VesselProximityModels and VesselProximityDistance, as 3D Slicer
// uses them: the SlicerExecutionModel XML they print on --xml is well formed and declares
// exactly the arguments they accept; a command line built from that XML by Slicer's rules runs
// and hands its results back through the return-parameter file; bad input is one line on stderr,
// a non-zero exit and nothing written.
#include "vpBuiltInPhantom.h"
#include "vpCliDescription.h"
#include "vpInputError.h"
#include "vpStlFormat.h"
#include "vpTestSupport.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselMeshWriter.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <sys/wait.h>

namespace
{
namespace fs = std::filesystem;
using vp::test::Slurp;
using vp::test::ToolRun;

const std::string ModelsProgram = VP_CLI_MODELS;
const std::string DistanceProgram = VP_CLI_DISTANCE;

std::string Quote(const std::string& text)
{
  std::string quoted = "'";
  for (char c : text)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

/// Runs a program with exactly these arguments (no shell splitting), stdout and stderr kept apart.
ToolRun RunCli(const std::string& dir, const std::string& program, const std::vector<std::string>& args)
{
  std::string command = Quote(program);
  for (const auto& a : args)
  {
    command += " " + Quote(a);
  }
  const std::string out = dir + "/stdout.txt", err = dir + "/stderr.txt";
  const int status = std::system((command + " >" + out + " 2>" + err).c_str());
  return { WIFEXITED(status) ? WEXITSTATUS(status) : -1, Slurp(out), Slurp(err) };
}

int Lines(const std::string& text)
{
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

std::string Trim(const std::string& text)
{
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
  {
    return std::string();
  }
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::string Text(vtkXMLDataElement* element)
{
  return element && element->GetCharacterData() ? Trim(element->GetCharacterData()) : std::string();
}

// ---------------------------------------------------------------------------------------------
// The XML as Slicer's ModuleDescriptionParser reads it.

struct SemParameter
{
  std::string Tag, Name, Flag, LongFlag, Channel, Default, Label, Description;
  std::string TypeAttribute, CoordinateSystem, Multiple;
  int Index = -1;
  std::vector<std::string> Elements;
  bool HasConstraints = false;
  double Minimum = 0.0, Maximum = 0.0;

  bool Flagged() const { return !this->Flag.empty() || !this->LongFlag.empty(); }
  /// As ModuleDescription::HasReturnParameters sees one: a simple output without flag or index.
  bool IsReturn() const
  {
    static const std::set<std::string> simple = { "integer", "float", "double", "boolean", "string",
      "string-enumeration", "integer-vector", "float-vector", "double-vector", "string-vector" };
    return this->Channel == "output" && !this->Flagged() && this->Index < 0 && simple.count(this->Tag);
  }
};

struct SemModule
{
  std::vector<std::string> TopLevel; ///< element names under <executable>, in order
  std::map<std::string, std::string> Info;
  std::vector<SemParameter> Parameters;
  bool Parsed = false;
};

SemModule ParseSem(const std::string& xml)
{
  SemModule module;
  vtkNew<vtkXMLDataParser> parser;
  parser->SetIgnoreCharacterData(0);
  std::istringstream stream(xml);
  parser->SetStream(&stream);
  if (!parser->Parse() || !parser->GetRootElement())
  {
    return module;
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  module.Parsed = std::string(root->GetName()) == "executable";
  for (int i = 0; i < root->GetNumberOfNestedElements(); ++i)
  {
    vtkXMLDataElement* e = root->GetNestedElement(i);
    module.TopLevel.push_back(e->GetName());
    if (module.TopLevel.back() != "parameters")
    {
      module.Info[e->GetName()] = Text(e);
      continue;
    }
    for (int k = 0; k < e->GetNumberOfNestedElements(); ++k)
    {
      vtkXMLDataElement* p = e->GetNestedElement(k);
      const std::string tag = p->GetName();
      if (tag == "label" || tag == "description")
      {
        continue;
      }
      SemParameter sp;
      sp.Tag = tag;
      sp.TypeAttribute = p->GetAttribute("type") ? p->GetAttribute("type") : "";
      sp.CoordinateSystem = p->GetAttribute("coordinateSystem") ? p->GetAttribute("coordinateSystem") : "";
      sp.Multiple = p->GetAttribute("multiple") ? p->GetAttribute("multiple") : "";
      for (int m = 0; m < p->GetNumberOfNestedElements(); ++m)
      {
        vtkXMLDataElement* f = p->GetNestedElement(m);
        const std::string field = f->GetName();
        if (field == "name")
          sp.Name = Text(f);
        else if (field == "flag")
          sp.Flag = Text(f);
        else if (field == "longflag")
          sp.LongFlag = Text(f);
        else if (field == "index")
          sp.Index = std::stoi(Text(f));
        else if (field == "channel")
          sp.Channel = Text(f);
        else if (field == "default")
          sp.Default = Text(f);
        else if (field == "label")
          sp.Label = Text(f);
        else if (field == "description")
          sp.Description = Text(f);
        else if (field == "element")
          sp.Elements.push_back(Text(f));
        else if (field == "constraints")
        {
          sp.HasConstraints = true;
          sp.Minimum = std::stod(Text(f->FindNestedElementWithName("minimum")));
          sp.Maximum = std::stod(Text(f->FindNestedElementWithName("maximum")));
        }
      }
      // Slicer strips the dashes a longflag or flag may be written with.
      sp.LongFlag.erase(0, sp.LongFlag.find_first_not_of('-'));
      sp.Flag.erase(0, sp.Flag.find_first_not_of('-'));
      module.Parameters.push_back(sp);
    }
  }
  return module;
}

/// The command line vtkSlicerCLIModuleLogic builds for an executable module: the return file
/// first, then flagged parameters in document order (scalars and enumerations always; strings,
/// vectors, files and data only when set; booleans bare when true), then index arguments.
/// values holds what the user set in the module panel; everything else keeps its default.
std::vector<std::string> SlicerCommandLine(const SemModule& module, const std::map<std::string, std::string>& values,
  const std::string& returnFile)
{
  std::vector<std::string> args;
  if (std::any_of(module.Parameters.begin(), module.Parameters.end(), [](const SemParameter& p) { return p.IsReturn(); }))
  {
    args = { "--returnparameterfile", returnFile };
  }
  auto valueOf = [&](const SemParameter& p) {
    const auto it = values.find(p.Name);
    return it == values.end() ? p.Default : it->second;
  };
  static const std::set<std::string> whenSet = { "file", "directory", "string", "integer-vector", "float-vector",
    "double-vector", "string-vector", "image", "geometry", "transform", "table", "measurement", "point", "region" };
  std::map<int, std::string> indexed;
  for (const SemParameter& p : module.Parameters)
  {
    if (p.IsReturn())
    {
      continue;
    }
    const std::string value = valueOf(p);
    if (p.Index >= 0)
    {
      indexed[p.Index] = value;
      continue;
    }
    const std::string flag = p.LongFlag.empty() ? "-" + p.Flag : "--" + p.LongFlag;
    if (p.Tag == "boolean")
    {
      if (value == "true")
      {
        args.push_back(flag);
      }
    }
    else if (!whenSet.count(p.Tag) || !value.empty())
    {
      args.insert(args.end(), { flag, value });
    }
  }
  for (const auto& entry : indexed)
  {
    args.push_back(entry.second);
  }
  return args;
}

std::map<std::string, std::string> ReadReturnFile(const std::string& file)
{
  std::map<std::string, std::string> values;
  std::istringstream lines(Slurp(file));
  for (std::string line; std::getline(lines, line);)
  {
    const auto eq = line.find('=');
    if (eq != std::string::npos)
    {
      values[Trim(line.substr(0, eq))] = Trim(line.substr(eq + 1));
    }
  }
  return values;
}

double Number(const std::map<std::string, std::string>& values, const std::string& name)
{
  const auto it = values.find(name);
  return it == values.end() ? std::nan("") : std::stod(it->second);
}

/// A labelmap as Slicer writes one for a CLI: NRRD, 16-bit, LPS space, raw little-endian voxels.
/// 24^3 voxels of 1 mm, origin (-12,-12,-12): a ball of 64 (portal vein by TotalSegmentator's
/// value) at (-5,-5,0), one of 63 (inferior vena cava, the hepatic_vein class) at (5,5,0), and
/// one of 7 (no class in the built-in table) at (5,-5,5).
std::string WriteLabelmap(const std::string& dir)
{
  const std::string path = dir + "/labels.nrrd";
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\n"
         "type: short\n"
         "dimension: 3\n"
         "space: left-posterior-superior\n"
         "sizes: 24 24 24\n"
         "space directions: (1,0,0) (0,1,0) (0,0,1)\n"
         "kinds: domain domain domain\n"
         "endian: little\n"
         "encoding: raw\n"
         "space origin: (-12,-12,-12)\n\n";
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i)
      {
        const double p[3] = { i - 12.0, j - 12.0, k - 12.0 };
        auto within = [&](double x, double y, double z, double r) {
          return (p[0] - x) * (p[0] - x) + (p[1] - y) * (p[1] - y) + (p[2] - z) * (p[2] - z) <= r * r;
        };
        const std::int16_t label = within(-5, -5, 0, 4) ? 64 : within(5, 5, 0, 4) ? 63 : within(5, -5, 5, 3) ? 7 : 0;
        const unsigned char bytes[2] = { static_cast<unsigned char>(label & 0xff), static_cast<unsigned char>(label >> 8) };
        out.write(reinterpret_cast<const char*>(bytes), 2);
      }
  return path;
}

class SlicerCli : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("slicercli");
    for (const auto& vessel : vp::MakeBuiltInVessels())
    {
      vtkNew<vtkVesselMeshWriter> writer;
      writer->SetFileName(this->Dir + "/" + vessel.first + ".stl");
      writer->SetInputData(vessel.second);
      writer->Write();
    }
    this->Labelmap = WriteLabelmap(this->Dir);
    // Values 64, 7, 63 to three classes, in this order.
    this->LabelTable = this->Dir + "/table.json";
    std::ofstream(this->LabelTable) << R"({"classes":[
      {"class":"portal_vein","values":[64]},
      {"class":"hepatic_artery","values":[7]},
      {"class":"hepatic_vein","values":[63]}]})";
  }

  SemModule Xml(const std::string& program)
  {
    const ToolRun r = RunCli(this->Dir, program, { "--xml" });
    EXPECT_EQ(r.ExitCode, 0) << r.Err;
    EXPECT_EQ(r.Err, "");
    return ParseSem(r.Out);
  }

  std::string Phantom(const std::string& cls) const { return this->Dir + "/" + cls + ".stl"; }

  /// What a Slicer user sets in each module's panel for a full run.
  std::map<std::string, std::string> ModelsValues(const std::string& out) const
  {
    return { { "inputVolume", this->Labelmap }, { "outputDirectory", out }, { "labelTable", this->LabelTable } };
  }
  std::map<std::string, std::string> DistanceValues() const
  {
    return { { "portalVein", this->Phantom("portal_vein") }, { "hepaticArtery", this->Phantom("hepatic_artery") },
      { "hepaticVein", this->Phantom("hepatic_vein") }, { "tip", "30,0,10" }, { "axis", "0,0,-1" },
      { "report", this->Dir + "/report.json" } };
  }

  std::string Dir, Labelmap, LabelTable;
};

/// Element order, required elements, unique names, a way to pass every non-return parameter,
/// enumeration defaults among their elements, defaults within constraints, indices 0..n-1.
void ExpectWellFormedSem(const SemModule& m, const std::string& program)
{
  SCOPED_TRACE(program);
  ASSERT_TRUE(m.Parsed) << "root is not <executable>, or the XML does not parse";
  const std::vector<std::string> head = { "category", "title", "description", "version", "documentation-url", "license",
    "contributor", "acknowledgements" };
  ASSERT_GT(m.TopLevel.size(), head.size());
  EXPECT_EQ(std::vector<std::string>(m.TopLevel.begin(), m.TopLevel.begin() + 8), head);
  for (std::size_t i = head.size(); i < m.TopLevel.size(); ++i)
  {
    EXPECT_EQ(m.TopLevel[i], "parameters");
  }
  EXPECT_EQ(m.Info.at("category"), "IGT");
  EXPECT_FALSE(m.Info.at("title").empty());
  EXPECT_FALSE(m.Info.at("description").empty());
  EXPECT_FALSE(m.Info.at("version").empty());
  ASSERT_FALSE(m.Parameters.empty());

  static const std::set<std::string> tags = { "integer", "float", "double", "boolean", "string", "integer-vector",
    "float-vector", "double-vector", "string-vector", "string-enumeration", "integer-enumeration", "float-enumeration",
    "double-enumeration", "point", "pointfile", "region", "file", "directory", "image", "geometry", "transform", "table",
    "measurement" };
  std::set<std::string> names, flags;
  std::set<int> indices;
  for (const SemParameter& p : m.Parameters)
  {
    SCOPED_TRACE(p.Name);
    EXPECT_TRUE(tags.count(p.Tag)) << p.Tag;
    EXPECT_FALSE(p.Name.empty());
    EXPECT_TRUE(names.insert(p.Name).second) << "name used twice";
    EXPECT_FALSE(p.Label.empty());
    EXPECT_FALSE(p.Description.empty());
    if (p.IsReturn())
    {
      EXPECT_FALSE(p.Flagged()) << "return parameters are not passed";
    }
    else
    {
      EXPECT_TRUE(p.Flagged() || p.Index >= 0) << "no flag, longflag or index: Slicer could not pass it";
    }
    if (!p.LongFlag.empty())
    {
      EXPECT_TRUE(flags.insert("--" + p.LongFlag).second) << "longflag used twice";
    }
    if (!p.Flag.empty())
    {
      EXPECT_TRUE(flags.insert("-" + p.Flag).second) << "flag used twice";
    }
    if (p.Index >= 0)
    {
      EXPECT_FALSE(p.Flagged());
      EXPECT_TRUE(indices.insert(p.Index).second);
    }
    if (p.Tag.find("-enumeration") != std::string::npos)
    {
      ASSERT_FALSE(p.Elements.empty());
      EXPECT_NE(std::find(p.Elements.begin(), p.Elements.end(), p.Default), p.Elements.end())
        << "default " << p.Default << " is not an element";
    }
    if (p.HasConstraints)
    {
      EXPECT_LE(p.Minimum, std::stod(p.Default));
      EXPECT_GE(p.Maximum, std::stod(p.Default));
    }
    if (p.Tag == "image" || p.Tag == "geometry" || p.Tag == "file" || p.Tag == "directory")
    {
      EXPECT_TRUE(p.Channel == "input" || p.Channel == "output") << "data needs a channel";
    }
    if (p.Tag == "point")
    {
      EXPECT_EQ(p.CoordinateSystem, "lps") << "the engines work in LPS";
      EXPECT_EQ(p.Multiple, "false");
    }
  }
  int expected = 0;
  for (int index : indices)
  {
    EXPECT_EQ(index, expected++);
  }
}
} // namespace

// ---------------------------------------------------------------------------------------------

TEST_F(SlicerCli, XmlIsWellFormedSlicerExecutionModel)
{
  const SemModule models = this->Xml(ModelsProgram);
  ExpectWellFormedSem(models, ModelsProgram);
  const SemModule distance = this->Xml(DistanceProgram);
  ExpectWellFormedSem(distance, DistanceProgram);

  // The parameters the brief promised, with the types Slicer needs to offer the right nodes.
  auto find = [](const SemModule& m, const std::string& name) {
    const auto it = std::find_if(m.Parameters.begin(), m.Parameters.end(), [&](const SemParameter& p) { return p.Name == name; });
    return it == m.Parameters.end() ? SemParameter() : *it;
  };
  EXPECT_EQ(find(models, "inputVolume").Tag, "image");
  EXPECT_EQ(find(models, "inputVolume").TypeAttribute, "label");
  EXPECT_EQ(find(models, "inputVolume").Index, 0);
  EXPECT_EQ(find(models, "outputDirectory").Channel, "output");
  EXPECT_EQ(find(models, "smoothing").Default, "0.5");
  EXPECT_EQ(find(models, "space").Elements, (std::vector<std::string>{ "LPS", "RAS" }));
  EXPECT_TRUE(find(models, "numberOfModels").IsReturn());
  for (const char* vessel : { "portalVein", "hepaticArtery", "hepaticVein" })
  {
    EXPECT_EQ(find(distance, vessel).Tag, "geometry");
    EXPECT_EQ(find(distance, vessel).TypeAttribute, "model");
  }
  EXPECT_EQ(find(distance, "tip").Tag, "point");
  EXPECT_EQ(find(distance, "method").Elements, (std::vector<std::string>{ "exact", "zbuffer", "both", "auto" }));
  EXPECT_EQ(find(distance, "rangeMm").Default, "50");
  for (const char* result : { "nearestClass", "nearestDistanceMm", "portalVeinDistanceMm", "hepaticArteryDistanceMm",
         "hepaticVeinDistanceMm", "errorBoundMm" })
  {
    EXPECT_TRUE(find(distance, result).IsReturn()) << result;
  }
}

TEST_F(SlicerCli, HelpListsEveryDeclaredParameter)
{
  for (const std::string& program : { ModelsProgram, DistanceProgram })
  {
    const SemModule m = this->Xml(program);
    const ToolRun r = RunCli(this->Dir, program, { "--help" });
    ASSERT_EQ(r.ExitCode, 0) << r.Err;
    for (const SemParameter& p : m.Parameters)
    {
      EXPECT_NE(r.Out.find(p.Name), std::string::npos) << program << " --help does not list " << p.Name;
      if (!p.LongFlag.empty())
      {
        EXPECT_NE(r.Out.find("--" + p.LongFlag), std::string::npos) << p.LongFlag;
      }
    }
  }
}

// Each declared parameter, given on its own beside the required ones, is accepted and the run
// succeeds; each element of an enumeration too.
TEST_F(SlicerCli, AcceptsEveryParameterItDeclares)
{
  struct Program
  {
    std::string Path;
    std::map<std::string, std::string> Values;
    std::vector<std::string> Required; // parameters of the minimal run
  };
  const std::vector<Program> programs = {
    { ModelsProgram, this->ModelsValues(this->Dir + "/accept_models"), { "inputVolume", "outputDirectory" } },
    { DistanceProgram, this->DistanceValues(), { "portalVein", "tip" } },
  };
  for (const Program& program : programs)
  {
    const SemModule m = this->Xml(program.Path);
    auto argumentsOf = [&](const SemParameter& p, const std::string& value) {
      if (p.Index >= 0)
        return std::vector<std::string>{ value };
      const std::string flag = p.LongFlag.empty() ? "-" + p.Flag : "--" + p.LongFlag;
      return p.Tag == "boolean" ? std::vector<std::string>{ flag } : std::vector<std::string>{ flag, value };
    };
    std::vector<std::string> base;
    for (const SemParameter& p : m.Parameters)
    {
      if (std::count(program.Required.begin(), program.Required.end(), p.Name))
      {
        const auto more = argumentsOf(p, program.Values.at(p.Name));
        base.insert(p.Index >= 0 ? base.end() : base.begin(), more.begin(), more.end());
      }
    }
    const ToolRun minimal = RunCli(this->Dir, program.Path, base);
    EXPECT_EQ(minimal.ExitCode, 0) << minimal.Err;
    for (const SemParameter& p : m.Parameters)
    {
      if (p.IsReturn() || std::count(program.Required.begin(), program.Required.end(), p.Name))
      {
        continue;
      }
      std::vector<std::string> values = p.Elements;
      if (values.empty())
      {
        const auto it = program.Values.find(p.Name);
        values = { it != program.Values.end() ? it->second : p.Default };
      }
      for (const std::string& value : values)
      {
        SCOPED_TRACE(program.Path + " " + p.Name + " " + value);
        std::vector<std::string> args = argumentsOf(p, value);
        args.insert(args.end(), base.begin(), base.end());
        const ToolRun r = RunCli(this->Dir, program.Path, args);
        EXPECT_EQ(r.Err.find("unknown"), std::string::npos) << r.Err;
        if (r.ExitCode == 4)
        {
          // zbuffer and both need a Vulkan device; without one the refusal says so.
          EXPECT_NE(r.Err.find("Vulkan"), std::string::npos) << r.Err;
          continue;
        }
        EXPECT_EQ(r.ExitCode, 0) << r.Err;
        EXPECT_EQ(r.Err, "") << "Slicer logs anything on stderr as an error";
      }
    }
  }
}

TEST_F(SlicerCli, RefusesWhatItDoesNotDeclare)
{
  const std::string tip = "30,0,10";
  struct Case
  {
    std::string Program;
    std::vector<std::string> Args;
    std::string Named;
  };
  const std::vector<std::string> models = { this->Labelmap, "--outputDirectory", this->Dir + "/refused" };
  const std::vector<std::string> distance = { "--portalVein", this->Phantom("portal_vein"), "--tip", tip };
  auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  const std::vector<Case> cases = {
    { ModelsProgram, with(models, { "--notAParameter", "1" }), "--notAParameter" },
    { ModelsProgram, with(models, { "-q", "1" }), "-q" },
    { ModelsProgram, with(models, { "--tip", tip }), "--tip" },                  // the other program's
    { ModelsProgram, with(models, { "--numberOfModels", "3" }), "--numberOfModels" }, // an output
    { ModelsProgram, with(models, { "--smoothing-iterations", "5" }), "--smoothing-iterations" }, // models' own spelling
    { ModelsProgram, with(models, { "second.nrrd" }), "second.nrrd" },
    { DistanceProgram, with(distance, { "--smoothing", "0.5" }), "--smoothing" },
    { DistanceProgram, with(distance, { "--vessels", "portal_vein=x.stl" }), "--vessels" },
    { DistanceProgram, with(distance, { "--nearestDistanceMm", "1" }), "--nearestDistanceMm" },
    { DistanceProgram, with(distance, { "extra.stl" }), "extra.stl" },
  };
  for (const Case& c : cases)
  {
    const ToolRun r = RunCli(this->Dir, c.Program, c.Args);
    EXPECT_EQ(r.ExitCode, 2) << c.Named << ": " << r.Err;
    EXPECT_EQ(Lines(r.Err), 1) << r.Err;
    EXPECT_NE(r.Err.find(c.Named), std::string::npos) << r.Err;
  }
  EXPECT_FALSE(fs::exists(this->Dir + "/refused")) << "nothing written";
}

TEST_F(SlicerCli, ModelsRunsAsSlicerRunsIt)
{
  const SemModule m = this->Xml(ModelsProgram);
  const std::string out = this->Dir + "/models", params = this->Dir + "/models.params";
  const auto args = SlicerCommandLine(m, this->ModelsValues(out), params);
  ASSERT_EQ(args.back(), this->Labelmap) << "the index argument comes last";
  const ToolRun r = RunCli(this->Dir, ModelsProgram, args);
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(r.Err, "") << "progress goes to stdout: Slicer logs stderr as errors";

  const auto values = ReadReturnFile(params);
  EXPECT_EQ(values.at("numberOfModels"), "3");
  EXPECT_EQ(values.at("modelClasses"), "portal_vein,hepatic_artery,hepatic_vein");
  EXPECT_NE(r.Out.find("numberOfModels = 3"), std::string::npos) << "results printed too";

  const auto doc = nlohmann::json::parse(Slurp(out + "/models.json"));
  EXPECT_EQ(doc["space"], "LPS");
  EXPECT_EQ(doc["parameters"]["smoothing"], 0.5);
  EXPECT_EQ(doc["parameters"]["smoothing_iterations"], 20);
  // Each model sits where its ball is in the labelmap's LPS frame.
  const std::map<std::string, std::array<double, 3>> centres = { { "portal_vein", { -5, -5, 0 } },
    { "hepatic_vein", { 5, 5, 0 } }, { "hepatic_artery", { 5, -5, 5 } } };
  for (const auto& c : centres)
  {
    SCOPED_TRACE(c.first);
    const std::string stl = out + "/" + c.first + ".stl";
    EXPECT_EQ(vp::ParseSpaceTag(Slurp(stl).substr(0, 80)), vp::MeshSpace::LPS);
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(stl);
    reader->Read();
    double bounds[6];
    reader->GetOutput()->GetBounds(bounds);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR((bounds[2 * a] + bounds[2 * a + 1]) / 2, c.second[a], 0.5) << "axis " << a;
    }
  }

  // The built-in table knows 64 and 63 by value, not 7; RAS flips the files' frame.
  auto defaults = this->ModelsValues(this->Dir + "/models_ras");
  defaults.erase("labelTable");
  defaults["space"] = "RAS";
  const ToolRun ras = RunCli(this->Dir, ModelsProgram, SlicerCommandLine(m, defaults, params));
  ASSERT_EQ(ras.ExitCode, 0) << ras.Err;
  EXPECT_EQ(ReadReturnFile(params).at("numberOfModels"), "2");
  EXPECT_EQ(ReadReturnFile(params).at("modelClasses"), "portal_vein,hepatic_vein");
  EXPECT_EQ(vp::ParseSpaceTag(Slurp(this->Dir + "/models_ras/portal_vein.stl").substr(0, 80)), vp::MeshSpace::RAS);
}

// The phantom's known answers: the tip (30,0,10) is 4 mm above the portal vein torus (ring 30,
// tube 6, centre 0, axis S), 12.5 mm from the artery cylinder (axis y=0,z=25, radius 2.5), and
// sqrt(15^2+30^2+20^2) - 10 = 29.05 mm from the hepatic vein sphere (a faceted one: a little more).
TEST_F(SlicerCli, DistanceRunsAsSlicerRunsIt)
{
  const SemModule m = this->Xml(DistanceProgram);
  const std::string params = this->Dir + "/distance.params";
  const ToolRun r = RunCli(this->Dir, DistanceProgram, SlicerCommandLine(m, this->DistanceValues(), params));
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(r.Err, "");

  const auto v = ReadReturnFile(params);
  EXPECT_EQ(v.at("nearestClass"), "portal_vein");
  EXPECT_NEAR(Number(v, "nearestDistanceMm"), 4.0, 1e-6);
  EXPECT_EQ(v.at("nearestInside"), "false");
  EXPECT_NEAR(Number(v, "portalVeinDistanceMm"), 4.0, 1e-6);
  EXPECT_NEAR(Number(v, "hepaticArteryDistanceMm"), 12.5, 0.05);
  EXPECT_NEAR(Number(v, "hepaticVeinDistanceMm"), std::sqrt(1525.0) - 10.0, 0.1);
  EXPECT_GE(Number(v, "hepaticVeinDistanceMm"), std::sqrt(1525.0) - 10.0 - 1e-9) << "facets lie inside the sphere";
  EXPECT_NEAR(Number(v, "directionalDistanceMm"), 4.0, 1e-6) << "straight down onto the torus";
  EXPECT_EQ(Number(v, "errorBoundMm"), 0.0);
  EXPECT_EQ(v.at("methodUsed"), "exact");
  std::vector<double> point;
  std::istringstream text(v.at("nearestPoint"));
  for (std::string c; std::getline(text, c, ',');)
    point.push_back(std::stod(c));
  ASSERT_EQ(point.size(), 3u);
  EXPECT_NEAR(point[0], 30.0, 1e-6);
  EXPECT_NEAR(point[1], 0.0, 1e-6);
  EXPECT_NEAR(point[2], 6.0, 1e-6);

  // The report is the distance command's JSON, and says the same.
  const auto report = nlohmann::json::parse(Slurp(this->Dir + "/report.json"));
  EXPECT_EQ(report["method"], "exact");
  EXPECT_EQ(report["space"], "LPS");
  EXPECT_EQ(report["range_mm"], 50.0);
  const auto& res = report["results"][0];
  EXPECT_EQ(res["tip"], nlohmann::json::array({ 30.0, 0.0, 10.0 }));
  EXPECT_EQ(res["nearest"]["class"], "portal_vein");
  EXPECT_EQ(res["nearest"]["distance_mm"].get<double>(), Number(v, "nearestDistanceMm"));
  EXPECT_EQ(res["classes"]["hepatic_artery"]["distance_mm"].get<double>(), Number(v, "hepaticArteryDistanceMm"));
  EXPECT_EQ(res["classes"]["portal_vein"]["directional_mm"].get<double>(), 4.0);
  EXPECT_EQ(res["classes"].size(), 3u);
}

TEST_F(SlicerCli, DistanceMarksMissingAndOutOfRangeClassesWithMinusOne)
{
  const std::string params = this->Dir + "/partial.params";
  // Only the portal vein: the other classes were not given.
  ToolRun r = RunCli(this->Dir, DistanceProgram,
    { "--returnparameterfile", params, "--portalVein", this->Phantom("portal_vein"), "--tip", "30,0,10" });
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  auto v = ReadReturnFile(params);
  EXPECT_NEAR(Number(v, "portalVeinDistanceMm"), 4.0, 1e-6);
  EXPECT_EQ(v.at("hepaticArteryDistanceMm"), "-1");
  EXPECT_EQ(v.at("hepaticVeinDistanceMm"), "-1");
  EXPECT_EQ(v.at("directionalDistanceMm"), "-1") << "no axis given";

  // Everything beyond a 10 mm range.
  r = RunCli(this->Dir, DistanceProgram,
    { "--returnparameterfile", params, "--hepaticVein", this->Phantom("hepatic_vein"), "--portalVein",
      this->Phantom("portal_vein"), "--tip", "-80,0,40", "--axis", "1,0,0", "--rangeMm", "10" });
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  v = ReadReturnFile(params);
  EXPECT_EQ(v.at("nearestClass"), "none");
  EXPECT_EQ(v.at("nearestDistanceMm"), "-1");
  EXPECT_EQ(v.at("nearestPoint"), "");
  EXPECT_EQ(v.at("portalVeinDistanceMm"), "-1");
  EXPECT_EQ(v.at("hepaticVeinDistanceMm"), "-1");
  EXPECT_EQ(v.at("directionalDistanceMm"), "-1");
  const SemModule m = this->Xml(DistanceProgram);
  EXPECT_EQ(v.size(), static_cast<std::size_t>(std::count_if(m.Parameters.begin(), m.Parameters.end(),
                        [](const SemParameter& p) { return p.IsReturn(); })))
    << "every declared return parameter, every run";
}

// The models reach the logic as files, not as a CLASS=FILE list: a comma in a name is a name.
TEST_F(SlicerCli, DistanceTakesAModelWhoseFileNameHasAComma)
{
  const std::string comma = this->Dir + "/portal,vein.stl", params = this->Dir + "/comma.params";
  fs::copy_file(this->Phantom("portal_vein"), comma);
  const ToolRun r = RunCli(this->Dir, DistanceProgram, { "--returnparameterfile", params, "--portalVein", comma, "--tip", "30,0,10" });
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  const auto v = ReadReturnFile(params);
  EXPECT_EQ(v.at("nearestClass"), "portal_vein");
  EXPECT_NEAR(Number(v, "portalVeinDistanceMm"), 4.0, 1e-6);
}

// Bad input: exit 1 (a value or file) or 2 (usage), one line naming the parameter or file, and
// nothing written: no output folder, report or return-parameter file.
TEST_F(SlicerCli, BadInputIsOneLineAndWritesNothing)
{
  const std::string params = this->Dir + "/bad.params", report = this->Dir + "/bad.json";
  const std::string out = this->Dir + "/bad_models";
  const std::string badTable = this->Dir + "/bad_table.json";
  std::ofstream(badTable) << "{ not json";
  struct Case
  {
    std::string Program;
    std::vector<std::string> Args;
    int ExitCode;
    std::string Named, Problem;
  };
  const std::string pv = this->Phantom("portal_vein");
  const std::vector<Case> cases = {
    { DistanceProgram, { "--portalVein", this->Dir + "/missing.stl", "--tip", "1,2,3" }, 1, "missing.stl", "no such file" },
    { DistanceProgram, { "--portalVein", this->LabelTable, "--tip", "1,2,3" }, 1, "table.json", "" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--rangeMm", "far" }, 1, "--rangeMm", "expected a number" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--rangeMm", "0" }, 1, "--rangeMm", "between 1 and 1000" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--method", "brute" }, 1, "--method", "one of" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2" }, 1, "--tip", "three" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,nan" }, 1, "--tip", "finite" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--axis", "0,0,0" }, 1, "--axis", "zero" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--axis", "0,1" }, 1, "--axis", "three" },
    { DistanceProgram, { "--tip", "1,2,3" }, 2, "--portalVein", "at least one" },
    { DistanceProgram, { "--portalVein", pv }, 2, "--tip", "required" },
    { DistanceProgram, { "--portalVein", pv, "--tip" }, 2, "--tip", "needs a value" },
    { DistanceProgram, { "--portalVein", pv, "--portalVein", pv, "--tip", "1,2,3" }, 2, "--portalVein", "twice" },
    { ModelsProgram, { this->Dir + "/missing.nrrd", "--outputDirectory", out }, 1, "missing.nrrd", "" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--labelTable", badTable }, 1, "bad_table.json", "" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--smoothing", "2" }, 1, "--smoothing", "between 0 and 1" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--smoothingIterations", "2.5" }, 1,
      "--smoothingIterations", "whole number" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--space", "ijk" }, 1, "--space", "LPS, RAS" },
    { ModelsProgram, { this->Labelmap }, 2, "--outputDirectory", "required" },
    { ModelsProgram, { "--outputDirectory", out }, 2, "inputVolume", "required" },
  };
  for (const Case& c : cases)
  {
    std::vector<std::string> args = { "--returnparameterfile", params };
    if (c.Program == DistanceProgram)
    {
      args.insert(args.end(), { "--report", report });
    }
    args.insert(args.end(), c.Args.begin(), c.Args.end());
    const ToolRun r = RunCli(this->Dir, c.Program, args);
    SCOPED_TRACE(c.Named + " " + c.Problem);
    EXPECT_EQ(r.ExitCode, c.ExitCode) << r.Err;
    EXPECT_EQ(Lines(r.Err), 1) << r.Err;
    EXPECT_NE(r.Err.find(c.Named), std::string::npos) << r.Err;
    EXPECT_NE(r.Err.find(c.Problem), std::string::npos) << r.Err;
    EXPECT_FALSE(fs::exists(params)) << "no return-parameter file after a failure";
    EXPECT_FALSE(fs::exists(report)) << "no report after a failure";
    EXPECT_FALSE(fs::exists(out)) << "no output folder after a failure";
  }
  // No Vulkan device for the z-buffer (a loader pointed at a driver file that does not exist):
  // exit 4 with one line, as the help says, and nothing written.
  const ToolRun noDevice = RunCli(this->Dir, "/usr/bin/env",
    { "VK_ICD_FILENAMES=" + this->Dir + "/no-such-icd.json", DistanceProgram, "--returnparameterfile", params, "--report",
      report, "--portalVein", pv, "--tip", "1,2,3", "--method", "zbuffer" });
  EXPECT_EQ(noDevice.ExitCode, 4) << noDevice.Err;
  EXPECT_EQ(Lines(noDevice.Err), 1) << noDevice.Err;
  EXPECT_NE(noDevice.Err.find("no Vulkan device"), std::string::npos) << noDevice.Err;
  EXPECT_FALSE(fs::exists(params));
  EXPECT_FALSE(fs::exists(report));
}

// ---------------------------------------------------------------------------------------------
// The table library itself, in process.

namespace
{
vp::cli::ModuleDescription SmallTable()
{
  using vp::cli::Channel;
  using vp::cli::Parameter;
  using vp::cli::ParameterType;
  vp::cli::ModuleDescription d;
  d.Program = "Small";
  d.Category = "IGT";
  d.Title = "Tom & Jerry <test>";
  d.Description = "Text with ]]> inside, & \"quotes\".";
  d.Version = "1";
  vp::cli::ParameterGroup g{ "A & B", "group", {} };
  g.Parameters.push_back(Parameter(ParameterType::File, "input").SetIndex(0).SetChannel(Channel::Input).SetRequired()
                           .SetLabel("In <file>").SetDescription("x"));
  g.Parameters.push_back(Parameter(ParameterType::Boolean, "verbose").SetFlag("v").SetLongFlag("verbose")
                           .SetLabel("Verbose").SetDescription("x").SetDefault("false"));
  g.Parameters.push_back(Parameter(ParameterType::Integer, "count").SetLongFlag("count").SetLabel("Count")
                           .SetDescription("x").SetDefault("3").SetRange(1, 10, 1));
  g.Parameters.push_back(Parameter(ParameterType::Double, "result").SetChannel(Channel::Output).SetLabel("Result")
                           .SetDescription("x").SetDefault("-1"));
  d.Groups.push_back(g);
  return d;
}
} // namespace

TEST(SlicerCliTable, XmlEscapesTextAndKeepsCdataWhole)
{
  const auto d = SmallTable();
  vp::cli::ValidateDescription(d);
  const SemModule m = ParseSem(vp::cli::WriteXml(d));
  ASSERT_TRUE(m.Parsed);
  EXPECT_EQ(m.Info.at("title"), "Tom & Jerry <test>");
  EXPECT_EQ(m.Info.at("description"), "Text with ]]> inside, & \"quotes\".");
  ASSERT_EQ(m.Parameters.size(), 4u);
  EXPECT_EQ(m.Parameters[0].Label, "In <file>");
  EXPECT_EQ(m.Parameters[1].Flag, "v");
  EXPECT_TRUE(m.Parameters[3].IsReturn());
}

TEST(SlicerCliTable, ParsesSlicerStyleArguments)
{
  const auto d = SmallTable();
  auto parsed = vp::cli::ParseArguments(d, { "--returnparameterfile", "r.txt", "-v", "--count=7", "--", "-in.txt" });
  EXPECT_EQ(parsed.GetReturnParameterFile(), "r.txt");
  EXPECT_TRUE(parsed.GetBoolean("verbose"));
  EXPECT_EQ(parsed.GetInteger("count"), 7);
  EXPECT_EQ(parsed.GetString("input"), "-in.txt") << "after --, a leading dash is a file name";
  parsed = vp::cli::ParseArguments(d, { "in.txt" });
  EXPECT_FALSE(parsed.GetBoolean("verbose"));
  EXPECT_FALSE(parsed.IsSet("count"));
  EXPECT_EQ(parsed.GetInteger("count"), 3) << "the declared default";
  EXPECT_THROW(parsed.GetString("undeclared"), std::logic_error);
  EXPECT_THROW(vp::cli::ParseArguments(d, { "in.txt", "--verbose=true" }), vp::cli::UsageError);
  EXPECT_THROW(vp::cli::ParseArguments(d, { "in.txt", "--count", "11" }), vp::InputError);
  EXPECT_THROW(vp::cli::ParseArguments(d, { "in.txt", "--result", "1" }), vp::cli::UsageError);

  vp::cli::ReturnValues results(d);
  EXPECT_EQ(results.Text(), "result = -1\n") << "an unset result keeps its default";
  results.Set("result", 0.1);
  EXPECT_EQ(results.Text(), "result = 0.1\n") << "shortest exact form";
  EXPECT_THROW(results.Set("count", 1), std::logic_error) << "not a return parameter";
}

TEST(SlicerCliTable, BrokenTablesAreCaught)
{
  auto d = SmallTable();
  d.Groups[0].Parameters.push_back(vp::cli::Parameter(vp::cli::ParameterType::Float, "lost").SetLabel("L").SetDescription("x").SetDefault("1"));
  EXPECT_THROW(vp::cli::ValidateDescription(d), std::logic_error) << "no flag, no index, not an output";
  d = SmallTable();
  d.Groups[0].Parameters.push_back(vp::cli::Parameter(vp::cli::ParameterType::StringEnumeration, "pick").SetLongFlag("pick")
    .SetLabel("P").SetDescription("x").SetElements({ "a", "b" }).SetDefault("c"));
  EXPECT_THROW(vp::cli::ValidateDescription(d), std::logic_error) << "default not an element";
  d = SmallTable();
  d.Groups[0].Parameters.push_back(vp::cli::Parameter(vp::cli::ParameterType::Integer, "count2").SetLongFlag("count")
    .SetLabel("C").SetDescription("x").SetDefault("1"));
  EXPECT_THROW(vp::cli::ValidateDescription(d), std::logic_error) << "longflag used twice";
}
