#ifndef vpScalpelLoader_h
#define vpScalpelLoader_h

#include "vtkScalpelModel.h"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>

namespace vp
{
/// A tip and axis given by the user, in model coordinates; either may be missing.
struct ScalpelTipDefinition
{
  std::optional<std::array<double, 3>> TipMm;
  std::optional<std::array<double, 3>> Axis;
  /// What the front end calls the tip setting (its flag, for a command; the logic's own name
  /// TipMm by default): the scalpel's TipSource says the tip came from it, and a guessed tip
  /// says to give it there.
  std::string Source = "TipMm";
};

/// The tip definition file that belongs to a model: the model's name with .json in place of its
/// extension (Scalpel.stl -> Scalpel.json), in the same folder.
std::string ScalpelDefinitionFileFor(const std::string& modelFile);

/// Reads {"tip_mm": [x, y, z], "axis": [x, y, z]} ("axis" optional; other keys, such as the
/// calibration report `vesselproximity register pivot` writes around them, are ignored). Throws
/// vp::InputError naming the file for anything else.
ScalpelTipDefinition ReadScalpelDefinition(const std::string& jsonFile);
/// The same from a parsed document; jsonFile names it in messages.
ScalpelTipDefinition ParseScalpelDefinition(const nlohmann::json& root, const std::string& jsonFile);

/// Reads an instrument model (STL, VTK, VTP, PLY, OBJ) and defines its tip, in this order: the
/// given tip; else the definition file beside the model; else the automatic finder (the narrow
/// end of the principal axis). A missing axis is the principal axis, pointing from the model's
/// centre towards the tip. The choice is recorded in the scalpel's TipSource. Throws
/// vp::InputError naming the file on any problem.
vtkSmartPointer<vtkScalpelModel> LoadScalpel(const std::string& modelFile, const ScalpelTipDefinition& given);

/// LoadScalpel's choice of tip and axis for a model already read: the given tip, else the
/// definition that came with the model (beside, its Source naming it), else the finder.
/// modelName names the model in the finder's messages.
void DefineScalpelTip(vtkScalpelModel* scalpel, const ScalpelTipDefinition& given,
  const std::optional<ScalpelTipDefinition>& beside, const std::string& modelName);
} // namespace vp

#endif
