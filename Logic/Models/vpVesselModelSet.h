#ifndef vpVesselModelSet_h
#define vpVesselModelSet_h

#include "vpLabelStructure.h"
#include "vpModelRole.h"
#include "vpStlFormat.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace vp
{
class RunFolder;

/// How segmentations become vessel models, in the logic's names (defaults as Slicer's).
struct VesselModelParameters
{
  double SmoothingFactor = 0.5;  ///< windowed sinc, 0..1
  int SmoothingIterations = 20;  ///< 1..1000
  double DecimationFactor = 0.0; ///< fraction of triangles removed, 0..0.99
  MeshSpace FileSpace = MeshSpace::LPS;
  std::string LabelTableFile; ///< empty: the built-in Resources/VesselLabels.json
  /// A 3D Slicer colour table (.ctbl, ReadColorTableNames) naming the label values of unnamed
  /// labelmaps: its names are matched before the label table's values. Empty: none.
  std::string ColorTableFile;
  /// Whether inputs of different patients or frames of reference may be built into one set of
  /// models (default false: refused, ParameterError("AllowMixedPatients")).
  bool AllowMixedPatients = false;
  /// The classes to build (a Slicer CLI asked for one model needs no other); empty: every class
  /// the inputs hold.
  std::vector<std::string> Classes;
  /// Throws ParameterError naming the first setting out of its range.
  void Validate() const;
};

/// One model: a vessel class's (or the liver's), built from every structure the label table puts
/// in the class, or one tumour's, built from one structure or one connected piece of one.
struct VesselClassModel
{
  std::string ClassName;
  /// The file's stem and the id in columns and JSON: the class for a vessel, "tumour_03" for the
  /// third tumour.
  std::string Name;
  /// What the user reads: "portal vein", "tumour 03 (livertumor03)", "tumour 02 (livertumor,
  /// piece 2 of 3)".
  std::string DisplayName;
  ModelRole Role = ModelRole::Vessel;
  std::vector<const LabelStructure*> Structures; ///< into VesselModelSet::Imports or ::Pieces
  vtkSmartPointer<vtkPolyData> Surface;
  vtkIdType Voxels = 0;
  double VoxelVolumeMm3 = 0.0, VolumeMm3 = 0.0, AreaMm2 = 0.0, BuildMs = 0.0;
  std::array<double, 6> BoundsMm{};   ///< of the surface: xmin, xmax, ymin, ymax, zmin, zmax (LPS)
  std::array<double, 3> CentroidMm{}; ///< of the volume the surface encloses (LPS)
};

/// The models of one run of segmentations, in the label table's class order, with what was read
/// and what was left out. Moves but does not copy: the models point into the imports.
struct VesselModelSet
{
  VesselModelSet() = default;
  VesselModelSet(VesselModelSet&&) = default;
  VesselModelSet& operator=(VesselModelSet&&) = default;
  VesselModelSet(const VesselModelSet&) = delete;
  VesselModelSet& operator=(const VesselModelSet&) = delete;

  std::vector<std::string> Inputs;
  VesselModelParameters Parameters;
  std::vector<LabelStructures> Imports; ///< per input
  /// The connected pieces of tumour structures that hold several (SplitIntoComponents).
  std::vector<std::unique_ptr<LabelStructure>> Pieces;
  std::vector<VesselClassModel> Models;
  std::vector<std::string> ClassesFound; ///< every class the inputs hold, built or not (Parameters.Classes)
  std::vector<const LabelStructure*> Unmapped; ///< structures the table has no class for
  double ReadMs = 0.0, TotalMs = 0.0;
};

/// What a long build says as it goes ("portal_vein: 1234 voxels -> 5678 triangles in 12 ms"), with
/// the share of the work done by then, 0 to 1 (reading the inputs is taken as 0.4 of it, building
/// the classes' surfaces as the rest), for a progress bar (Slicer's <filter-progress>).
using ProgressReporter = std::function<void(const std::string& line, double fractionDone)>;

/// Reads each input (a folder of DICOM label series, a DICOM SEG, NRRD, .seg.nrrd or NIfTI
/// labelmap), maps its structures to classes through the label table, and builds one closed
/// surface per vessel class and one per tumour structure or connected piece of one
/// (vtkVesselModelBuilder) with its volume, area, bounds and centroid. Nothing is written.
/// Throws InputError naming the input when nothing in it is a vessel or the liver, and
/// ParameterError for a setting out of range.
VesselModelSet BuildVesselModels(
  const std::vector<std::string>& inputs, const VesselModelParameters& parameters, const ProgressReporter& progress);

/// models.json: the space, inputs, parameters, per model its id, class, role, display name,
/// sources, voxels, triangles, volume, area, bounds, centroid, file and surface check, every file
/// of the run, the unmapped structures and the times.
nlohmann::json VesselModelsJson(const VesselModelSet& set);

/// Writes <id>.stl for each model and models.json through the run's folder, which holds this
/// run whole afterwards (or the previous one as it was, when this throws).
void WriteVesselModels(const VesselModelSet& set, RunFolder& run);
/// The same files into a folder that a larger run puts in place (the demo's models/).
void WriteVesselModelFiles(const VesselModelSet& set, const std::string& folder);
} // namespace vp

#endif
