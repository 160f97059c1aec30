#include "vpDefaultScalpel.h"

#include "vpOutputFile.h"
#include "CusaHandpiece_json.h"
#include "CusaHandpiece_stl.h"
#include "vpInputError.h"
#include "vpIndexedMesh.h"
#include "vpStlFormat.h"

#include <filesystem>

namespace vp
{

std::string WriteDefaultScalpel(const std::string& folder)
{
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
  {
    throw InputError(folder, "cannot create folder: " + ec.message());
  }
  const std::string stl = folder + "/CusaHandpiece.stl";
  WriteFileAtomically(stl, std::string(reinterpret_cast<const char*>(CusaHandpiece_stl), CusaHandpiece_stl_size));
  WriteFileAtomically(
    folder + "/CusaHandpiece.json", std::string(reinterpret_cast<const char*>(CusaHandpiece_json), CusaHandpiece_json_size));
  return stl;
}
vtkSmartPointer<vtkScalpelModel> MakeDefaultScalpel(const ScalpelTipDefinition& given)
{
  const StlSoup soup = ParseStl(reinterpret_cast<const char*>(CusaHandpiece_stl), CusaHandpiece_stl_size, "CusaHandpiece.stl");
  auto scalpel = vtkSmartPointer<vtkScalpelModel>::New();
  std::size_t dropped = 0;
  scalpel->SetModel(BuildIndexedMesh(soup.Coordinates.data(), soup.Coordinates.size() / 9, &dropped));
  const auto* json = reinterpret_cast<const char*>(CusaHandpiece_json);
  std::optional<ScalpelTipDefinition> beside =
    ParseScalpelDefinition(nlohmann::json::parse(json, json + CusaHandpiece_json_size), "CusaHandpiece.json");
  beside->Source = "CusaHandpiece.json";
  DefineScalpelTip(scalpel, given, beside, "CusaHandpiece.stl");
  return scalpel;
}
} // namespace vp
