// The Slicer CLI entry points, VesselProximityModels and VesselProximityDistance, as 3D Slicer
// uses them: the SlicerExecutionModel XML they print on --xml is well formed and declares
// exactly the arguments they accept; a command line built from that XML by Slicer's rules runs
// and hands its results back through the return-parameter file; bad input is one line on stderr,
// a non-zero exit and nothing written.
#include "vpBuiltInPhantom.h"
#include "vpCliDescription.h"
#include "vpDefaultScalpel.h"
#include "vpItkTransformFile.h"
#include "vpMarkupsFile.h"
#include "vpInputError.h"
#include "vpStlFormat.h"
#include "vpTestSupport.h"
#include "vtkVesselMeshReader.h"
#include "vtkScalpelModel.h"
#include "vtkVesselMeshWriter.h"

#include <vtkDelimitedTextReader.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkTable.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
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
const std::string TrackProgram = VP_CLI_TRACK;

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
  const int status = std::system((command + " >" + Quote(out) + " 2>" + Quote(err)).c_str());
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
  std::map<std::string, std::string> Attributes; ///< every attribute of the tag, as written
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
  std::string Text;                  ///< the document as printed
  std::vector<std::string> TopLevel; ///< element names under <executable>, in order
  std::map<std::string, std::string> Info;
  std::vector<SemParameter> Parameters;
  bool Parsed = false;
};

SemModule ParseSem(const std::string& xml)
{
  SemModule module;
  module.Text = xml;
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
      for (int a = 0; a < p->GetNumberOfAttributes(); ++a)
      {
        sp.Attributes[p->GetAttributeName(a)] = p->GetAttributeValue(a);
      }
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
    "double-vector", "string-vector", "image", "geometry", "transform", "table", "measurement", "pointfile", "point", "region" };
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
/// 24^3 voxels of 1 mm, origin (-12,-12,-12): four balls with the given values, the portal vein
/// at (-5,-5,0), the hepatic vein at (5,5,0), the hepatic artery at (5,-5,5), the liver at
/// (-5,5,-4) (a value 0 leaves that ball out).
struct BallValues
{
  int PortalVein, HepaticVein, HepaticArtery, Liver;
};

std::string WriteLabelmap(const std::string& dir, const std::string& name, const BallValues& v)
{
  const std::string path = dir + "/" + name;
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
        const std::int16_t label = within(-5, -5, 0, 4) ? v.PortalVein
          : within(5, 5, 0, 4)                          ? v.HepaticVein
          : within(5, -5, 5, 3)                         ? v.HepaticArtery
          : within(-5, 5, -4, 3)                        ? v.Liver
                                                        : 0;
        const unsigned char bytes[2] = { static_cast<unsigned char>(label & 0xff), static_cast<unsigned char>(label >> 8) };
        out.write(reinterpret_cast<const char*>(bytes), 2);
      }
  return path;
}

/// Where each ball's model must lie, in the labelmap's LPS frame.
const std::map<std::string, std::array<double, 3>> BallCentres = { { "portal_vein", { -5, -5, 0 } },
  { "hepatic_vein", { 5, 5, 0 } }, { "hepatic_artery", { 5, -5, 5 } }, { "liver", { -5, 5, -4 } } };

/// A colour table as Slicer's vtkMRMLColorTableStorageNode writes one for a CLI.
std::string WriteColorTable(const std::string& path, const std::vector<std::pair<int, std::string>>& names)
{
  std::ofstream out(path);
  out << "# Color table file " << path << "\n# " << names.size() + 1 << " values\n0 Background 0 0 0 0\n";
  for (const auto& [value, name] : names)
  {
    out << value << " " << name << " 128 174 128 255\n";
  }
  return path;
}

/// Checks a model Slicer would read back (VTK's STL reader): its header names LPS and it sits
/// where its ball is.
void ExpectModelAt(const std::string& stl, const std::array<double, 3>& centre)
{
  SCOPED_TRACE(stl);
  ASSERT_TRUE(fs::exists(stl));
  EXPECT_EQ(vp::ParseSpaceTag(Slurp(stl).substr(0, 80)), vp::MeshSpace::LPS);
  vtkNew<vtkSTLReader> reader;
  reader->SetFileName(stl.c_str());
  reader->Update();
  ASSERT_GT(reader->GetOutput()->GetNumberOfPolys(), 100);
  double bounds[6];
  reader->GetOutput()->GetBounds(bounds);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR((bounds[2 * a] + bounds[2 * a + 1]) / 2, centre[a], 0.5) << "axis " << a;
  }
}

/// The progress Slicer reads from stdout: a start, fractions that never go back, and the end.
void ExpectFilterProgress(const std::string& out)
{
  EXPECT_NE(out.find("<filter-start><filter-name>"), std::string::npos) << out;
  EXPECT_NE(out.find("<filter-comment>"), std::string::npos) << out;
  EXPECT_NE(out.find("<filter-progress>1</filter-progress>\n<filter-end>"), std::string::npos) << out;
  double last = -1.0;
  int count = 0;
  for (std::size_t at = out.find("<filter-progress>"); at != std::string::npos; at = out.find("<filter-progress>", at + 1))
  {
    const double fraction = std::stod(out.substr(at + 17));
    EXPECT_GE(fraction, last);
    EXPECT_LE(fraction, 1.0);
    last = fraction;
    ++count;
  }
  EXPECT_GE(count, 3);
}

class SlicerCli : public ::testing::Test
{
protected:
  void SetUp() override
  {
    // Slicer's temporary folder can be anywhere a user's name and language put it.
    this->Dir = vp::test::MakeTempDir("slicercli") + "/Slicer's temp, Überprüfung";
    fs::create_directories(this->Dir);
    for (const auto& vessel : vp::MakeBuiltInVessels())
    {
      vtkNew<vtkVesselMeshWriter> writer;
      writer->SetFileName(this->Dir + "/" + vessel.first + ".stl");
      writer->SetInputData(vessel.second);
      writer->Write();
    }
    // 64 portal vein and 63 inferior vena cava by TotalSegmentator's values, 7 in no built-in
    // class, 5 the liver.
    this->Labelmap = WriteLabelmap(this->Dir, "labels.nrrd", { 64, 63, 7, 5 });
    // Values 64, 7, 63, 5 to four classes, in this order.
    this->LabelTable = this->Dir + "/table.json";
    std::ofstream(this->LabelTable) << R"({"classes":[
      {"class":"portal_vein","values":[64]},
      {"class":"hepatic_artery","values":[7]},
      {"class":"hepatic_vein","values":[63]},
      {"class":"liver","values":[5]}]})";
    this->ColorTable = WriteColorTable(this->Dir + "/12345_vtkMRMLColorTableNodeB.ctbl",
      { { 5, "Liver" }, { 7, "Hepatic_artery" }, { 63, "Hepatic_vein" }, { 64, "Portal_vein" } });
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
    return { { "inputVolume", this->Labelmap }, { "outputDirectory", out }, { "labelTable", this->LabelTable },
      { "colorTable", this->ColorTable }, { "portalVeinModel", this->Temporary("vtkMRMLModelNodeB.stl") },
      { "hepaticArteryModel", this->Temporary("vtkMRMLModelNodeC.stl") },
      { "hepaticVeinModel", this->Temporary("vtkMRMLModelNodeD.stl") }, { "liverModel", this->Temporary("vtkMRMLModelNodeE.stl") } };
  }
  std::map<std::string, std::string> DistanceValues() const
  {
    return { { "portalVein", this->Phantom("portal_vein") }, { "hepaticArtery", this->Phantom("hepatic_artery") },
      { "hepaticVein", this->Phantom("hepatic_vein") }, { "tip", "30,0,10" }, { "axis", "0,0,-1" },
      { "report", this->Dir + "/report.json" }, { "closestPoints", this->Temporary("vtkMRMLMarkupsFiducialNodeB.mrk.json") },
      { "resultsTable", this->Temporary("vtkMRMLTableNodeB.csv") } };
  }
  /// A name as Slicer gives a node's temporary file: <pid>_<node ID, digits as letters><ext>.
  std::string Temporary(const std::string& node) const { return this->Dir + "/BCDE_" + node; }

  std::string Dir, Labelmap, LabelTable, ColorTable;
};

/// ModuleDescriptionParser's own rules for the attributes of each tag (SlicerExecutionModel,
/// ModuleDescriptionParser.cxx, startElement): an attribute it does not list for the tag is an
/// error that fails the whole parse for the data tags (Slicer then does not offer the module),
/// and its values are checked: multiple, hidden and aggregate are true or false; an image's,
/// geometry's, transform's and table's type one of its few; a point's coordinate system ijk, lps
/// or ras (Slicer itself runs only lps and ras).
void ExpectParserAcceptsAttributes(const SemParameter& p)
{
  static const std::map<std::string, std::set<std::string>> allowed = {
    { "point", { "multiple", "coordinateSystem" } },
    { "pointfile", { "multiple", "type", "fileExtensions", "coordinateSystem" } },
    { "geometry", { "multiple", "aggregate", "type", "fileExtensions", "reference" } },
    { "table", { "multiple", "reference", "hidden", "type", "fileExtensions" } },
    { "transform", { "multiple", "type", "fileExtensions", "reference" } },
    { "image", { "multiple", "type", "fileExtensions", "hidden", "reference" } },
    { "file", { "multiple", "fileExtensions" } },
    { "directory", { "multiple" } },
  };
  static const std::map<std::string, std::set<std::string>> types = {
    { "image", { "any", "scalar", "label", "tensor", "diffusion-weighted", "vector", "signal", "multichannel",
                 "dynamic-contrast-enhanced" } },
    { "geometry", { "fiberbundle", "model" } },
    { "transform", { "linear", "nonlinear", "bspline" } },
    { "table", { "color" } },
    { "pointfile", { "point", "line", "angle", "curve", "any" } },
  };
  const auto tag = allowed.find(p.Tag);
  for (const auto& [name, value] : p.Attributes)
  {
    SCOPED_TRACE(p.Tag + " " + name + "=" + value);
    if (tag != allowed.end())
    {
      EXPECT_TRUE(tag->second.count(name)) << "the parser refuses this attribute on this tag";
    }
    else
    {
      EXPECT_TRUE(name == "hidden" || name == "multiple") << "ignored by the parser: a mistake";
    }
    if (name == "multiple" || name == "hidden" || name == "aggregate")
    {
      EXPECT_TRUE(value == "true" || value == "false");
    }
    if (name == "type" && types.count(p.Tag))
    {
      EXPECT_TRUE(types.at(p.Tag).count(value)) << "not a type the parser knows";
    }
    if (name == "coordinateSystem")
    {
      EXPECT_TRUE(value == "lps" || value == "ras");
    }
  }
}

/// GenerateCLP (what Slicer's own CLIs are built with) pastes the XML into C++: the whole file
/// as one string with only '"' escaped, the contributor, acknowledgements and version raw inside
/// quotes, string defaults with '"' escaped but line breaks raw. So: no backslash anywhere, no
/// carriage return, no '"' or line break in those three, none in a default; numeric defaults are
/// C++ numbers; the first line starts with "<?xml " (a byte-order mark fails the parser).
void ExpectGenerateClpCompiles(const SemModule& m)
{
  EXPECT_EQ(m.Text.rfind("<?xml ", 0), 0u);
  EXPECT_EQ(m.Text.find('\\'), std::string::npos) << "a backslash becomes an escape sequence";
  EXPECT_EQ(m.Text.find('\r'), std::string::npos);
  for (const char* field : { "contributor", "acknowledgements", "version" })
  {
    const std::string text = m.Info.at(field);
    EXPECT_EQ(text.find_first_of("\"\n"), std::string::npos) << field << ": " << text;
  }
  for (const SemParameter& p : m.Parameters)
  {
    EXPECT_EQ(p.Default.find('\n'), std::string::npos) << p.Name;
    if (p.Tag == "integer" || p.Tag == "float" || p.Tag == "double")
    {
      std::size_t used = 0;
      EXPECT_NO_THROW(std::stod(p.Default, &used)) << p.Name;
      EXPECT_EQ(used, p.Default.size()) << p.Name << " default " << p.Default << " is not a C++ number";
    }
  }
}

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
  EXPECT_EQ(m.Info.at("documentation-url").rfind("file:///", 0), 0u) << m.Info.at("documentation-url");
  EXPECT_TRUE(fs::exists(m.Info.at("documentation-url").substr(7))) << "the link leads to the README";
  EXPECT_EQ(m.Info.at("license"), "Apache-2.0");
  EXPECT_NE(m.Info.at("acknowledgements").find("Noborio"), std::string::npos);
  ExpectGenerateClpCompiles(m);
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
    static const std::set<std::string> data = { "image", "geometry", "file", "directory", "transform", "table", "pointfile" };
    if (data.count(p.Tag))
    {
      EXPECT_TRUE(p.Channel == "input" || p.Channel == "output") << "data needs a channel (Slicer shows no widget without one)";
    }
    if (p.Tag == "point" || p.Tag == "pointfile")
    {
      EXPECT_EQ(p.CoordinateSystem, "lps") << "the engines work in LPS";
      EXPECT_EQ(p.Multiple, "false");
    }
    ExpectParserAcceptsAttributes(p);
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
  EXPECT_EQ(find(distance, "tipFile").Tag, "pointfile");
  EXPECT_EQ(find(distance, "scalpelPose").Tag, "transform");
  EXPECT_EQ(find(distance, "scalpelPose").TypeAttribute, "linear");
  EXPECT_EQ(find(distance, "closestPoints").Tag, "pointfile");
  EXPECT_EQ(find(distance, "closestPoints").Channel, "output");
  EXPECT_EQ(find(distance, "resultsTable").Tag, "table");
  EXPECT_EQ(find(distance, "resultsTable").Channel, "output");
  EXPECT_EQ(find(models, "colorTable").Tag, "table");
  EXPECT_EQ(find(models, "colorTable").TypeAttribute, "color");
  for (const char* model : { "portalVeinModel", "hepaticArteryModel", "hepaticVeinModel", "liverModel" })
  {
    EXPECT_EQ(find(models, model).Tag, "geometry");
    EXPECT_EQ(find(models, model).TypeAttribute, "model");
    EXPECT_EQ(find(models, model).Channel, "output");
  }
  const SemModule track = this->Xml(TrackProgram);
  ExpectWellFormedSem(track, TrackProgram);
  EXPECT_EQ(find(track, "registration").Tag, "transform");
  EXPECT_EQ(find(track, "framesTable").Tag, "table");
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
  for (const std::string& program : { ModelsProgram, DistanceProgram, TrackProgram })
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
  auto trackValues = std::map<std::string, std::string>{ { "portalVein", this->Phantom("portal_vein") },
    { "hepaticArtery", this->Phantom("hepatic_artery") }, { "hepaticVein", this->Phantom("hepatic_vein") },
    { "poses", VP_SOURCE_DIR "/Testing/Data/approach_poses.csv" }, { "framesTable", this->Dir + "/accept_frames.csv" },
    { "summary", this->Dir + "/accept_summary.json" }, { "plot", this->Dir + "/accept.png" },
    { "outputDirectory", this->Dir + "/accept_track" }, { "scalpel", this->Dir + "/scalpel.stl" },
    { "registration", this->Dir + "/identity.tfm" }, { "tumour", this->Phantom("hepatic_vein") } };
  vp::WriteDefaultScalpel(this->Dir);
  fs::rename(this->Dir + "/CusaHandpiece.stl", this->Dir + "/scalpel.stl");
  fs::remove(this->Dir + "/CusaHandpiece.json");
  vp::WriteItkLinearTransform(this->Dir + "/identity.tfm", { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 });
  const std::vector<Program> programs = {
    { ModelsProgram, this->ModelsValues(this->Dir + "/accept_models"), { "inputVolume", "outputDirectory", "colorTable" } },
    { DistanceProgram, this->DistanceValues(), { "portalVein", "tip" } },
    { TrackProgram, trackValues, { "portalVein", "poses" } },
  };
  // Alternatives to the minimal run's --tip, each run in its own test (a second tip is refused).
  const std::set<std::string> alternatives = { "tipFile", "scalpelPose", "scalpel" };
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
      if (p.IsReturn() || std::count(program.Required.begin(), program.Required.end(), p.Name) ||
        (program.Path == DistanceProgram && alternatives.count(p.Name)))
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
        if (p.Name == "strict" && r.ExitCode == 1)
        {
          // These poses pass far from the phantom's vessels (a warning): strict refuses them, as
          // TrackSaysADoubtfulRecordingAndStrictRefusesIt checks.
          EXPECT_NE(r.Err.find("strict refuses the run"), std::string::npos) << r.Err;
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
  const auto values = this->ModelsValues(out);
  const auto args = SlicerCommandLine(m, values, params);
  ASSERT_EQ(args.back(), this->Labelmap) << "the index argument comes last";
  const ToolRun r = RunCli(this->Dir, ModelsProgram, args);
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(r.Err, "") << "progress goes to stdout: Slicer logs stderr as errors";
  ExpectFilterProgress(r.Out);

  const auto returned = ReadReturnFile(params);
  EXPECT_EQ(returned.at("numberOfModels"), "4");
  EXPECT_EQ(returned.at("modelClasses"), "portal_vein,hepatic_artery,hepatic_vein,liver");
  EXPECT_NE(r.Out.find("numberOfModels = 4"), std::string::npos) << "results printed too";
  // Every declared output was produced: each model node's file, and the folder.
  for (const auto& [parameter, cls] : std::map<std::string, std::string>{ { "portalVeinModel", "portal_vein" },
         { "hepaticArteryModel", "hepatic_artery" }, { "hepaticVeinModel", "hepatic_vein" }, { "liverModel", "liver" } })
  {
    ExpectModelAt(values.at(parameter), BallCentres.at(cls));
    ExpectModelAt(out + "/" + cls + ".stl", BallCentres.at(cls));
  }

  const auto doc = nlohmann::json::parse(Slurp(out + "/models.json"));
  EXPECT_EQ(doc["space"], "LPS");
  EXPECT_EQ(doc["parameters"]["smoothing"], 0.5);
  EXPECT_EQ(doc["parameters"]["smoothing_iterations"], 20);

  // The built-in table knows 64, 63 and 5 by value, not 7; RAS flips the files' frame.
  auto defaults = this->ModelsValues(this->Dir + "/models_ras");
  for (const char* name : { "labelTable", "colorTable", "portalVeinModel", "hepaticArteryModel", "hepaticVeinModel", "liverModel" })
  {
    defaults.erase(name);
  }
  defaults["space"] = "RAS";
  const ToolRun ras = RunCli(this->Dir, ModelsProgram, SlicerCommandLine(m, defaults, params));
  ASSERT_EQ(ras.ExitCode, 0) << ras.Err;
  EXPECT_EQ(ReadReturnFile(params).at("numberOfModels"), "3");
  EXPECT_EQ(ReadReturnFile(params).at("modelClasses"), "portal_vein,hepatic_vein,liver");
  EXPECT_EQ(vp::ParseSpaceTag(Slurp(this->Dir + "/models_ras/portal_vein.stl").substr(0, 80)), vp::MeshSpace::RAS);
}

// What a Slicer user has: a labelmap volume whose values mean something only through its colour
// table (Slicer's own: 1 liver, 2 portal vein, 3 hepatic vein, 4 hepatic artery), and model nodes
// to fill. No label table, no folder.
TEST_F(SlicerCli, ModelsNamesTheLabelsByTheColourTableAndFillsModelNodes)
{
  const SemModule m = this->Xml(ModelsProgram);
  const std::string labelmap = WriteLabelmap(this->Dir, "BCDE_vtkMRMLLabelMapVolumeNodeB.nrrd", { 2, 3, 4, 1 });
  const std::string colours = WriteColorTable(this->Dir + "/BCDE_vtkMRMLColorTableNodeC.ctbl",
    { { 1, "liver" }, { 2, "portal_vein" }, { 3, "hepatic_vein" }, { 4, "hepatic_artery" }, { 9, "tumor" } });
  const std::string params = this->Dir + "/colours.params";
  std::map<std::string, std::string> values = { { "inputVolume", labelmap },
    { "portalVeinModel", this->Temporary("vtkMRMLModelNodeF.stl") }, { "hepaticArteryModel", this->Temporary("vtkMRMLModelNodeG.stl") },
    { "hepaticVeinModel", this->Temporary("vtkMRMLModelNodeH.stl") } };

  // Without the colour table the values name nothing, and the refusal says what to give.
  ToolRun r = RunCli(this->Dir, ModelsProgram, SlicerCommandLine(m, values, params));
  EXPECT_EQ(r.ExitCode, 1) << r.Err;
  EXPECT_EQ(Lines(r.Err), 1) << r.Err;
  EXPECT_NE(r.Err.find("names none of its values (label 1, label 2, label 3, label 4)"), std::string::npos) << r.Err;
  EXPECT_NE(r.Err.find("give the labelmap's colour table"), std::string::npos) << r.Err;
  EXPECT_FALSE(fs::exists(values.at("portalVeinModel"))) << "nothing written";

  values["colorTable"] = colours;
  r = RunCli(this->Dir, ModelsProgram, SlicerCommandLine(m, values, params));
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(r.Err, "");
  ExpectFilterProgress(r.Out);
  // Only the classes asked for are built (the liver is in the labelmap, but no node asked for it).
  EXPECT_EQ(ReadReturnFile(params).at("modelClasses"), "portal_vein,hepatic_vein,hepatic_artery");
  EXPECT_EQ(r.Out.find("models: liver:"), std::string::npos) << r.Out;
  EXPECT_NE(r.Out.find("models: portal_vein:"), std::string::npos) << r.Out;
  ExpectModelAt(values.at("portalVeinModel"), BallCentres.at("portal_vein"));
  ExpectModelAt(values.at("hepaticArteryModel"), BallCentres.at("hepatic_artery"));
  ExpectModelAt(values.at("hepaticVeinModel"), BallCentres.at("hepatic_vein"));

  // A model node asked for a structure the labelmap lacks: refused, nothing written.
  fs::remove(values.at("portalVeinModel"));
  const std::string noLiver = WriteLabelmap(this->Dir, "BCDE_vtkMRMLLabelMapVolumeNodeD.nrrd", { 2, 3, 4, 0 });
  values["inputVolume"] = noLiver;
  values["liverModel"] = this->Temporary("vtkMRMLModelNodeI.stl");
  r = RunCli(this->Dir, ModelsProgram, SlicerCommandLine(m, values, params));
  EXPECT_EQ(r.ExitCode, 1) << r.Err;
  EXPECT_EQ(Lines(r.Err), 1) << r.Err;
  EXPECT_NE(r.Err.find("no liver structure in the labelmap (asked for by --liverModel)"), std::string::npos) << r.Err;
  EXPECT_FALSE(fs::exists(values.at("portalVeinModel")));
  EXPECT_FALSE(fs::exists(values.at("liverModel")));

  // A labelmap of the portal vein alone (one value): the colour table's name for it counts.
  const std::string alone = WriteLabelmap(this->Dir, "BCDE_vtkMRMLLabelMapVolumeNodeE.nrrd", { 2, 0, 0, 0 });
  r = RunCli(this->Dir, ModelsProgram, SlicerCommandLine(m,
    { { "inputVolume", alone }, { "colorTable", colours }, { "portalVeinModel", values.at("portalVeinModel") } }, params));
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(ReadReturnFile(params).at("modelClasses"), "portal_vein");
  ExpectModelAt(values.at("portalVeinModel"), BallCentres.at("portal_vein"));
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
  EXPECT_EQ(v.at("hepaticArteryDistanceMm"), "") << "no value for a model not given, not 0 or -1";
  EXPECT_EQ(v.at("hepaticVeinDistanceMm"), "");
  EXPECT_EQ(v.at("directionalDistanceMm"), "") << "no axis given";

  // A tip inside: the distance is signed, minus its depth. The phantom's hepatic vein is a ball
  // of radius 10 at (45, 30, -10); 4 mm above its centre the tip is 6 mm deep.
  r = RunCli(this->Dir, DistanceProgram,
    { "--returnparameterfile", params, "--hepaticVein", this->Phantom("hepatic_vein"), "--tip", "45,30,-6" });
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  v = ReadReturnFile(params);
  EXPECT_NEAR(Number(v, "hepaticVeinDistanceMm"), -6.0, 0.1);
  EXPECT_NEAR(Number(v, "nearestDistanceMm"), -6.0, 0.1);
  EXPECT_EQ(v.at("nearestInside"), "true");

  // Everything beyond a 10 mm range.
  r = RunCli(this->Dir, DistanceProgram,
    { "--returnparameterfile", params, "--hepaticVein", this->Phantom("hepatic_vein"), "--portalVein",
      this->Phantom("portal_vein"), "--tip", "-80,0,40", "--axis", "1,0,0", "--rangeMm", "10" });
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  v = ReadReturnFile(params);
  EXPECT_EQ(v.at("nearestClass"), "none");
  EXPECT_EQ(v.at("nearestDistanceMm"), "");
  EXPECT_EQ(v.at("nearestPoint"), "");
  EXPECT_EQ(v.at("portalVeinDistanceMm"), "");
  EXPECT_EQ(v.at("hepaticVeinDistanceMm"), "");
  EXPECT_EQ(v.at("directionalDistanceMm"), "");
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

/// A table Slicer would read back (VTK's delimited-text reader, the first row the header).
vtkSmartPointer<vtkTable> ReadCsvTable(const std::string& file)
{
  vtkNew<vtkDelimitedTextReader> reader;
  reader->SetFileName(file.c_str());
  reader->SetFieldDelimiterCharacters(",");
  reader->SetHaveHeaders(true);
  reader->Update();
  return reader->GetOutput();
}

/// The row of a table whose first column holds key.
vtkIdType RowOf(vtkTable* table, const std::string& key)
{
  for (vtkIdType row = 0; row < table->GetNumberOfRows(); ++row)
  {
    if (table->GetValue(row, 0).ToString() == key)
    {
      return row;
    }
  }
  return -1;
}

// The IGT way: the tool's transform node (tool to patient, as Slicer writes it: ITK's LPS "from
// parent") carries the built-in scalpel's tip to (30,0,10); the closest points come back as a point
// list node and the answers as a table node, each read as Slicer reads them. A tip point list
// (.fcsv in LPS, markups JSON in RAS) gives the same answers.
TEST_F(SlicerCli, DistanceTakesTheToolTransformAndReturnsPointsAndATable)
{
  const SemModule m = this->Xml(DistanceProgram);
  const std::string params = this->Dir + "/igt.params";
  const auto scalpel = vp::MakeDefaultScalpel();
  const double* tipModel = scalpel->GetTipMm();
  // Tool to patient: a quarter turn about S, then the translation that puts the tip at (30,0,10).
  const std::array<double, 3> rotated = { -tipModel[1], tipModel[0], tipModel[2] };
  const vp::Matrix4 toolToPatient = { 0, -1, 0, 30 - rotated[0], 1, 0, 0, 0 - rotated[1], 0, 0, 1, 10 - rotated[2], 0, 0, 0, 1 };
  const std::string pose = this->Temporary("vtkMRMLLinearTransformNodeB.h5");
  vp::WriteItkLinearTransform(pose, vp::InvertTransform(toolToPatient));

  auto values = this->DistanceValues();
  values.erase("tip");
  values.erase("axis");
  values["scalpelPose"] = pose;
  ToolRun r = RunCli(this->Dir, DistanceProgram, SlicerCommandLine(m, values, params));
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(r.Err, "");
  ExpectFilterProgress(r.Out); // Slicer's progress bar moves while the models are read
  auto v = ReadReturnFile(params);
  EXPECT_NEAR(Number(v, "portalVeinDistanceMm"), 4.0, 1e-6);
  EXPECT_NEAR(Number(v, "hepaticArteryDistanceMm"), 12.5, 0.05);

  // The point list: the tip, then per class its closest point, labelled, in LPS.
  const auto points = vp::ReadMarkupsPoints(values.at("closestPoints"));
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points[0].Label, "tip");
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(points[0].PositionLps[a], (std::array<double, 3>{ 30, 0, 10 })[a], 1e-9);
    EXPECT_NEAR(points[1].PositionLps[a], (std::array<double, 3>{ 30, 0, 6 })[a], 1e-6);
  }
  EXPECT_EQ(points[1].Label, "portal_vein 4 mm");
  const auto markups = nlohmann::json::parse(Slurp(values.at("closestPoints")));
  EXPECT_EQ(markups["markups"][0]["type"], "Fiducial") << "Slicer makes the node class from it";
  EXPECT_EQ(markups["markups"][0]["coordinateSystem"], "LPS");

  // The table, typed by its schema.
  const auto table = ReadCsvTable(values.at("resultsTable"));
  ASSERT_EQ(table->GetNumberOfRows(), 3);
  ASSERT_EQ(table->GetNumberOfColumns(), 10);
  const vtkIdType portal = RowOf(table, "portal_vein");
  ASSERT_GE(portal, 0);
  EXPECT_EQ(table->GetValueByName(portal, "distance_mm").ToDouble(), Number(v, "portalVeinDistanceMm"));
  EXPECT_EQ(table->GetValueByName(portal, "inside").ToString(), "false");
  EXPECT_NEAR(table->GetValueByName(portal, "closest_z_lps").ToDouble(), 6.0, 1e-6);
  EXPECT_EQ(table->GetValueByName(portal, "engine").ToString(), "exact");
  // Slicer's storage node looks for table.schema.csv beside table.csv (vtkMRMLTableStorageNode::
  // GenerateSchemaFileName), comma-separated as the table is.
  const std::string schema = Slurp(this->Temporary("vtkMRMLTableNodeB.schema.csv"));
  EXPECT_EQ(schema.rfind("columnName,type,unitLabel,nullValue\n", 0), 0u) << schema;
  EXPECT_NE(schema.find("\ndistance_mm,double,mm,nan\n"), std::string::npos) << schema;
  EXPECT_NE(schema.find("\nclass,string,,\n"), std::string::npos) << schema;
  EXPECT_EQ(std::count(schema.begin(), schema.end(), '\n'), 11) << "a row for each of the 10 columns";

  // A z-buffer answer is labelled with the interval its truth lies in, the exact 4 mm inside it.
  auto zbuffer = values;
  zbuffer["method"] = "zbuffer";
  zbuffer["closestPoints"] = this->Temporary("vtkMRMLMarkupsFiducialNodeZ.mrk.json");
  zbuffer.erase("resultsTable");
  zbuffer.erase("report");
  const ToolRun z = RunCli(this->Dir, DistanceProgram, SlicerCommandLine(m, zbuffer, params));
  if (z.ExitCode == 4)
  {
    std::cout << "[  SKIPPED ] the z-buffer's label: " << z.Err;
  }
  else
  {
    ASSERT_EQ(z.ExitCode, 0) << z.Err;
    const std::string label = vp::ReadMarkupsPoints(zbuffer.at("closestPoints")).at(1).Label;
    double low = 0, high = 0;
    ASSERT_EQ(std::sscanf(label.c_str(), "portal_vein %lf-%lf mm", &low, &high), 2) << label;
    EXPECT_LE(low, 4.0) << label;
    EXPECT_GE(high, 4.0) << label;
    EXPECT_NEAR(high - low, 2 * Number(ReadReturnFile(params), "errorBoundMm"), 0.011) << label;
  }
  // A tip point list, as Slicer writes one: .fcsv in LPS, and markups JSON in RAS.
  const std::string fcsv = this->Temporary("vtkMRMLMarkupsFiducialNodeC.fcsv");
  std::ofstream(fcsv) << "# Markups fiducial file version = 5.8\n# CoordinateSystem = LPS\n"
                         "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n"
                         "1,30,0,10,0,0,0,1,1,1,0,F-1,,\n";
  const std::string json = this->Temporary("vtkMRMLMarkupsFiducialNodeD.mrk.json");
  std::ofstream(json) << R"({"markups":[{"type":"Fiducial","coordinateSystem":"RAS","controlPoints":[
    {"label":"F-1","position":[-30.0,0.0,10.0],"positionStatus":"defined"}]}]})";
  for (const std::string& file : { fcsv, json })
  {
    SCOPED_TRACE(file);
    r = RunCli(this->Dir, DistanceProgram,
      { "--returnparameterfile", params, "--portalVein", this->Phantom("portal_vein"), "--tipFile", file });
    ASSERT_EQ(r.ExitCode, 0) << r.Err;
    v = ReadReturnFile(params);
    EXPECT_NEAR(Number(v, "portalVeinDistanceMm"), 4.0, 1e-6);
  }
}

// A recorded session reviewed in Slicer: three poses of the built-in scalpel lowering its tip
// from (30,0,20) to (30,0,10): the portal vein torus (top at z 6) 14, 9, 4 mm below, the artery
// cylinder (axis y=0, z=25, radius 2.5) 2.5, 7.5, 12.5 mm above.
TEST_F(SlicerCli, TrackRunsAsSlicerRunsIt)
{
  const SemModule m = this->Xml(TrackProgram);
  ExpectWellFormedSem(m, TrackProgram);
  const auto scalpel = vp::MakeDefaultScalpel();
  const double* tip = scalpel->GetTipMm();
  const std::string poses = this->Dir + "/poses.csv";
  {
    std::ofstream out(poses);
    out << "time,x,y,z,qw,qx,qy,qz\n";
    for (int i = 0; i < 3; ++i)
    {
      out << 0.1 * i << "," << 30 - tip[0] << "," << -tip[1] << "," << 20 - 5 * i - tip[2] << ",1,0,0,0\n";
    }
  }
  const std::string params = this->Dir + "/track.params";
  const std::map<std::string, std::string> values = { { "portalVein", this->Phantom("portal_vein") },
    { "hepaticArtery", this->Phantom("hepatic_artery") }, { "hepaticVein", this->Phantom("hepatic_vein") },
    { "poses", poses }, { "framesTable", this->Temporary("vtkMRMLTableNodeC.csv") },
    { "summary", this->Dir + "/summary.json" }, { "plot", this->Dir + "/distance.png" },
    { "tumour", this->Phantom("hepatic_vein") } };
  const ToolRun r = RunCli(this->Dir, TrackProgram, SlicerCommandLine(m, values, params));
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_EQ(r.Err, "");
  ExpectFilterProgress(r.Out);
  const auto v = ReadReturnFile(params);
  EXPECT_EQ(v.at("frames"), "3");
  EXPECT_NEAR(Number(v, "portalVeinMinimumMm"), 4.0, 1e-6);
  EXPECT_NEAR(Number(v, "hepaticArteryMinimumMm"), 2.5, 0.05);
  EXPECT_NE(v.at("worstLevel"), "safe");
  // The phantom's hepatic vein as a tumour: a ball of radius 10 at (45, 30, -10), the tip at its
  // lowest (30, 0, 10) sqrt(15^2 + 30^2 + 20^2) - 10 = 29.05 mm from it.
  EXPECT_NEAR(Number(v, "tumourMinimumMm"), std::sqrt(15.0 * 15 + 30 * 30 + 20 * 20) - 10.0, 0.05);
  EXPECT_EQ(v.at("worstMarginLevel"), "clear");
  EXPECT_TRUE(v.at("worstLevelCause") == "tip" || v.at("worstLevelCause") == "instrument") << v.at("worstLevelCause");
  EXPECT_EQ(v.at("warnings"), "") << "poses among the vessels, in mm: nothing to doubt";
  const auto summaryJson = nlohmann::json::parse(Slurp(values.at("summary")));
  const auto& portal = summaryJson["classes"]["portal_vein"];
  const bool entered = portal["penetration_maximum"].is_object() && portal["penetration_maximum"]["depth_frame"].get<int>() >= 0;
  EXPECT_NEAR(Number(v, "portalVeinInstrumentMinimumMm"),
    entered ? -portal["penetration_maximum"]["depth_mm"].get<double>() : portal["surface_minimum"]["distance_mm"].get<double>(), 1e-4);

  const auto frames = ReadCsvTable(values.at("framesTable"));
  EXPECT_EQ(frames->GetNumberOfRows(), 3);
  // Typed for Slicer: a schema row for every column of the table, each with its type and unit.
  const std::string framesSchema = Slurp(this->Temporary("vtkMRMLTableNodeC.schema.csv"));
  EXPECT_EQ(std::count(framesSchema.begin(), framesSchema.end(), '\n'), frames->GetNumberOfColumns() + 1) << framesSchema;
  for (const char* row : { "\nframe,int,,\n", "\ntime,double,s,nan\n", "\nnearest_mm,double,mm,nan\n", "\ndanger_level,string,,\n",
         "\nportal_vein_inside,string,,\n", "\nportal_vein_penetration_volume_mm3,double,mm3,nan\n", "\nframe_ms,double,ms,nan\n",
         "\naxis_x,double,,nan\n" })
  {
    EXPECT_NE(framesSchema.find(row), std::string::npos) << row << framesSchema;
  }
  // The same poses through `vesselproximity track` (the same built-in handpiece and meshes, copied
  // to a folder whose name --vessels' list can hold): the same levels and distances, frame by frame.
  const std::string plain = vp::test::MakeTempDir("cli_track");
  for (const char* cls : { "portal_vein", "hepatic_artery", "hepatic_vein" })
  {
    fs::copy_file(this->Phantom(cls), plain + "/" + cls + ".stl");
  }
  fs::copy_file(poses, plain + "/poses.csv");
  const std::string handpiece = vp::WriteDefaultScalpel(plain + "/scalpel");
  const ToolRun track = vp::test::RunTool(plain, "track --vessels portal_vein=" + plain + "/portal_vein.stl,hepatic_artery=" +
    plain + "/hepatic_artery.stl,hepatic_vein=" + plain + "/hepatic_vein.stl --scalpel " + handpiece + " --poses " + plain +
    "/poses.csv -o " + plain + "/track");
  ASSERT_EQ(track.ExitCode, 0) << track.Err;
  const auto tracked = ReadCsvTable(plain + "/track/frames.csv");
  fs::remove_all(plain);
  ASSERT_EQ(tracked->GetNumberOfRows(), frames->GetNumberOfRows());
  for (vtkIdType row = 0; row < frames->GetNumberOfRows(); ++row)
  {
    for (const char* column : { "danger_level", "tip_level", "instrument_level", "level_class", "portal_vein_mm",
           "hepatic_artery_mm", "portal_vein_surface_mm", "hepatic_artery_penetration_volume_mm3" })
    {
      ASSERT_TRUE(frames->GetColumnByName(column) && tracked->GetColumnByName(column)) << column;
      EXPECT_EQ(frames->GetValueByName(row, column).ToString(), tracked->GetValueByName(row, column).ToString())
        << column << " of frame " << row;
    }
  }
  const auto summary = nlohmann::json::parse(Slurp(values.at("summary")));
  EXPECT_EQ(summary["frames"], 3);
  EXPECT_EQ(Slurp(values.at("plot")).substr(1, 3), "PNG");
  for (const auto& entry : fs::directory_iterator(this->Dir))
  {
    EXPECT_EQ(entry.path().filename().string().rfind(".vesselproximity-track-", 0), std::string::npos)
      << "the working folder is gone: " << entry.path();
  }
}

// A recording that looks misread (here: no pose near any vessel, as metres read as millimetres
// would be) is said in Warnings, with nothing on stderr; with strict it is refused in one line
// and nothing is written.
TEST_F(SlicerCli, TrackSaysADoubtfulRecordingAndStrictRefusesIt)
{
  const SemModule m = this->Xml(TrackProgram);
  const std::string poses = this->Dir + "/far.csv";
  std::ofstream(poses) << "time,x,y,z,qw,qx,qy,qz\n0,900,900,900,1,0,0,0\n0.1,901,900,900,1,0,0,0\n";
  for (const bool strict : { false, true })
  {
    const std::string params = this->Dir + "/far" + std::to_string(strict) + ".params";
    std::map<std::string, std::string> values = { { "portalVein", this->Phantom("portal_vein") }, { "poses", poses },
      { "framesTable", this->Temporary(strict ? "vtkMRMLTableNodeS.csv" : "vtkMRMLTableNodeF.csv") } };
    if (strict)
    {
      values["strict"] = "true";
    }
    const ToolRun r = RunCli(this->Dir, TrackProgram, SlicerCommandLine(m, values, params));
    if (!strict)
    {
      ASSERT_EQ(r.ExitCode, 0) << r.Err;
      EXPECT_EQ(r.Err, "");
      EXPECT_NE(ReadReturnFile(params).at("warnings"), "");
      EXPECT_EQ(ReadReturnFile(params).at("worstLevelCause"), "none");
      continue;
    }
    EXPECT_EQ(r.ExitCode, 1) << r.Err;
    EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << r.Err;
    EXPECT_NE(r.Err.find(poses + ": "), std::string::npos) << r.Err;
    EXPECT_NE(r.Err.find("strict refuses the run"), std::string::npos) << r.Err;
    EXPECT_FALSE(fs::exists(values.at("framesTable")));
    EXPECT_FALSE(fs::exists(params));
  }
}

// Bad input: exit 1 (a value or file) or 2 (usage), one line naming the parameter or file, and
// nothing written: no output folder, report or return-parameter file.
TEST_F(SlicerCli, BadInputIsOneLineAndWritesNothing)
{
  const std::string params = this->Dir + "/bad.params", report = this->Dir + "/bad.json";
  const std::string out = this->Dir + "/bad_models";
  const std::string badTable = this->Dir + "/bad_table.json";
  std::ofstream(badTable) << "{ not json";
  const std::string badFcsv = this->Dir + "/old.fcsv", badJson = this->Dir + "/bad.mrk.json", badColours = this->Dir + "/bad.ctbl";
  std::ofstream(badFcsv) << "F-1,30,0,10,1,1\n"; // Slicer 3's layout
  std::ofstream(badJson) << R"({"markups":[{"type":"Fiducial","controlPoints":[{"position":[1,2]}]}]})";
  std::ofstream(badColours) << "# Color table file x\n# 3 values\n1 liver 300 0 0 255\n";
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
    { DistanceProgram, { "--portalVein", pv }, 2, "--tip", "give the tip" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--tipFile", this->Dir + "/tip.fcsv" }, 2, "--tipFile",
      "only one" },
    { DistanceProgram, { "--portalVein", pv, "--tipFile", badFcsv }, 1, "old.fcsv", "version" },
    { DistanceProgram, { "--portalVein", pv, "--tipFile", badJson }, 1, "bad.mrk.json", "position" },
    { DistanceProgram, { "--portalVein", pv, "--scalpelPose", this->LabelTable }, 1, "table.json", "" },
    { DistanceProgram, { "--portalVein", pv, "--tip", "1,2,3", "--scalpel", pv }, 2, "--scalpel", "--scalpelPose" },
    { DistanceProgram, { "--portalVein", pv, "--tip" }, 2, "--tip", "needs a value" },
    { DistanceProgram, { "--portalVein", pv, "--portalVein", pv, "--tip", "1,2,3" }, 2, "--portalVein", "twice" },
    { ModelsProgram, { this->Dir + "/missing.nrrd", "--outputDirectory", out }, 1, "missing.nrrd", "" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--labelTable", badTable }, 1, "bad_table.json", "" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--smoothing", "2" }, 1, "--smoothing", "between 0 and 1" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--smoothingIterations", "2.5" }, 1,
      "--smoothingIterations", "whole number" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--space", "ijk" }, 1, "--space", "LPS, RAS" },
    { ModelsProgram, { this->Labelmap }, 2, "--outputDirectory", "give a model to create or an output folder" },
    { ModelsProgram, { this->Labelmap, "--outputDirectory", out, "--colorTable", badColours }, 1, "bad.ctbl", "line 3" },
    { TrackProgram, { "--portalVein", pv, "--poses", this->LabelTable, "--summary", report }, 1, "table.json", "" },
    { TrackProgram, { "--portalVein", pv }, 2, "--poses", "required" },
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
