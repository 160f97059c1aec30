#ifndef vpModelsFile_h
#define vpModelsFile_h

#include "vpModelRole.h"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vp
{
/// One surface of a models folder, as its models.json lists it.
struct ModelStructure
{
  std::string Name;      ///< the file's stem and the id in columns: "portal_vein", "tumour_03"
  std::string ClassName; ///< "portal_vein", "liver", "tumour"
  std::string Label;     ///< what the user sees: "portal vein", "tumour 03 (livertumor03)"
  ModelRole Role = ModelRole::Vessel;
  std::string File; ///< the surface, beside models.json
  std::optional<std::array<double, 6>> BoundsMm;   ///< xmin, xmax, ymin, ymax, zmin, zmax (LPS)
  std::optional<std::array<double, 3>> CentroidMm; ///< of the enclosed volume (LPS)
  double VolumeMm3 = 0.0;
};

/// A models folder written by `vesselproximity models` (or the cohort's models/ of a case).
struct ModelsFile
{
  std::string FileName; ///< the models.json read
  std::string Space;    ///< "LPS" or "RAS": the space the surface files are written in
  std::vector<ModelStructure> Structures;

  /// The structures of one role, in the file's order.
  std::vector<ModelStructure> WithRole(ModelRole role) const;
  /// The structure named name (its Name), or null.
  const ModelStructure* Find(const std::string& name) const;
};

/// Whether path is a models folder (holding models.json) or a models.json file: what --tumour
/// and --models take whole.
bool IsModelsPath(const std::string& path);

/// Reads a models folder or its models.json. Throws InputError naming the file for one that is
/// not a models.json (no "structures", a structure without a name, class or file, a name that
/// could not be a class's, a file outside the folder, a number that is not one).
ModelsFile ReadModelsFile(const std::string& folderOrJson);
/// The same from a models.json already parsed; fileName names it in errors and places its files.
ModelsFile ParseModelsFile(const nlohmann::json& doc, const std::string& fileName);
} // namespace vp

#endif
