#include "vpScalpelLoader.h"

#include "vpInputError.h"
#include "vpJsonFile.h"
#include "vpScalpelTipFinder.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace vp
{
namespace
{
std::array<double, 3> ReadVector(const nlohmann::json& value, const std::string& file, const char* key)
{
  if (!value.is_array() || value.size() != 3)
  {
    throw InputError(file, std::string(key) + ": expected an array of 3 numbers");
  }
  std::array<double, 3> v{};
  for (int i = 0; i < 3; ++i)
  {
    if (!value[i].is_number() || !std::isfinite(value[i].get<double>()))
    {
      throw InputError(file, std::string(key) + ": expected an array of 3 finite numbers");
    }
    v[i] = value[i].get<double>();
  }
  return v;
}

std::string PointText(const std::array<double, 3>& p)
{
  char text[96];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", p[0], p[1], p[2]);
  return text;
}
} // namespace

std::string ScalpelDefinitionFileFor(const std::string& modelFile)
{
  return std::filesystem::path(modelFile).replace_extension(".json").string();
}

ScalpelTipDefinition ReadScalpelDefinition(const std::string& jsonFile)
{
  return ParseScalpelDefinition(ReadJsonFile(jsonFile, "a scalpel tip definition"), jsonFile);
}

ScalpelTipDefinition ParseScalpelDefinition(const nlohmann::json& root, const std::string& jsonFile)
{
  if (!root.is_object() || !root.contains("tip_mm"))
  {
    throw InputError(jsonFile, "no \"tip_mm\" in it (expected {\"tip_mm\": [x, y, z], \"axis\": [x, y, z]})");
  }
  ScalpelTipDefinition definition;
  definition.TipMm = ReadVector(root.at("tip_mm"), jsonFile, "tip_mm");
  if (root.contains("axis"))
  {
    definition.Axis = ReadVector(root.at("axis"), jsonFile, "axis");
    const auto& a = *definition.Axis;
    if (!(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] > 0))
    {
      throw InputError(jsonFile, "axis: must not be the zero vector");
    }
  }
  return definition;
}

vtkSmartPointer<vtkScalpelModel> LoadScalpel(const std::string& modelFile, const ScalpelTipDefinition& given)
{
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(modelFile);
  reader->Read();
  auto scalpel = vtkSmartPointer<vtkScalpelModel>::New();
  scalpel->SetModel(reader->GetOutput());
  const std::string besideFile = ScalpelDefinitionFileFor(modelFile);
  std::error_code ec;
  std::optional<ScalpelTipDefinition> beside;
  // Whatever has that name is read (a folder or a pipe there is refused, not passed over).
  if (!given.TipMm && std::filesystem::exists(std::filesystem::symlink_status(besideFile, ec)))
  {
    beside = ReadScalpelDefinition(besideFile);
    beside->Source = std::filesystem::path(besideFile).filename().string();
  }
  DefineScalpelTip(scalpel, given, beside, modelFile);
  return scalpel;
}

void DefineScalpelTip(vtkScalpelModel* scalpel, const ScalpelTipDefinition& given,
  const std::optional<ScalpelTipDefinition>& beside, const std::string& modelName)
{
  ScalpelTipDefinition definition = given;
  std::string source = given.Source;
  if (!definition.TipMm && beside)
  {
    definition = *beside;
    if (given.Axis)
    {
      definition.Axis = given.Axis;
    }
    source = beside->Source;
  }
  if (definition.TipMm && definition.Axis)
  {
    const auto& a = *definition.Axis;
    scalpel->SetTipMm(definition.TipMm->data());
    scalpel->SetAxis(a[0], a[1], a[2]);
    scalpel->SetTipSource("tip " + PointText(*definition.TipMm) + " and axis from " + source);
    return;
  }
  // The finder gives the tip, or the principal axis that a tip given without an axis needs.
  const ScalpelTipEstimate estimate = FindScalpelTip(scalpel->GetModel(), modelName);
  if (!definition.TipMm)
  {
    scalpel->SetTipMm(estimate.TipMm.data());
    const auto& a = definition.Axis ? *definition.Axis : estimate.Axis;
    scalpel->SetAxis(a[0], a[1], a[2]);
    // The loader, not the finder, knows what the front end calls the tip setting.
    scalpel->SetTipSource(estimate.Description + (estimate.Ambiguous ? ": give the tip with " + given.Source + " or a JSON file" : ""));
    return;
  }
  const auto& tip = *definition.TipMm;
  scalpel->SetTipMm(tip.data());
  // Principal axis, oriented from the centre of the model towards the given tip.
  double along = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    along += (tip[i] - estimate.CentroidMm[i]) * estimate.Axis[i];
  }
  const double sign = along < 0 ? -1.0 : 1.0;
  scalpel->SetAxis(sign * estimate.Axis[0], sign * estimate.Axis[1], sign * estimate.Axis[2]);
  std::array<double, 3> axis{};
  scalpel->GetAxis(axis.data());
  scalpel->SetTipSource("tip " + PointText(tip) + " from " + source + ", axis " + PointText(axis) +
    " along the model's principal axis towards the tip");
}
} // namespace vp
