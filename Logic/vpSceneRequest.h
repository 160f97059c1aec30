#ifndef vpSceneRequest_h
#define vpSceneRequest_h

#include "vpDistanceEngineSettings.h"
#include "vpInstrumentMethod.h"
#include "vpScalpelLoader.h"
#include "vpTrackingSettings.h"
#include "vpVesselMeshSet.h"
#include "vtkScalpelPenetration.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkScalpelModel;

namespace vp
{
/// Everything a front end asks of a scene, in the logic's names: which vessel surfaces and how to
/// treat them, the scalpel and its tip, the engine and its settings, and the frame loop's
/// thresholds, hysteresis and budget. A front end fills one from its own options and hands it to
/// vtkVesselProximityLogic::OpenScene; the logic reads the files, builds the engines and checks
/// the settings against each other, and says what it found in a vp::OpenedScene.
///
/// Defaults: no vessel, the built-in CUSA handpiece with its own tip, the exact engine with its
/// own range, the whole instrument and its penetration measured, no comparison with the exact
/// engine, and vp::TrackingSettings' thresholds, hysteresis and budget.
struct SceneRequest
{
  /// Per vessel class, its surface (LPS mm, closed for inside/outside): Mesh when the front end
  /// has it in memory, else read from FileName. Classes are answered in this order.
  std::vector<NamedMesh> Vessels;
  /// Each vessel surface repaired (vtkVesselSurfaceRepair) before it is used; the report of each
  /// repair is in OpenedScene::Vessels.
  bool RepairVessels = false;
  /// The tumours to be resected, each under its id (NamedMesh::ClassName) with its surface (LPS
  /// mm, closed for inside/outside): Mesh, else read from FileName. The tip's resection margin
  /// (Tracking.Margin) is measured against each, exactly. Empty: none.
  std::vector<NamedMesh> Tumours;
  /// A liver surface to show beside the vessels (read; never measured). Empty: none.
  std::string LiverFile;
  /// The scalpel: a model already made, else its model file (STL, VTK, VTP, PLY, OBJ), else (both
  /// empty) the built-in CUSA handpiece.
  vtkSmartPointer<vtkScalpelModel> Scalpel;
  std::string ScalpelFile;
  /// The tip and axis in model coordinates, each optional: else the definition file beside the
  /// model, else found from the model's shape (ScalpelFile and the built-in handpiece only).
  ScalpelTipDefinition Tip;
  /// Which engine answers the tip, and its settings.
  DistanceEngineSettings Engine;
  /// Every frame also answered by the exact engine, for the accuracy check, when the engine made
  /// is not the exact one (method auto without a device makes it the exact one).
  bool CompareWithExact = false;
  /// The whole instrument measured beside the tip.
  bool ComputeSurfaceDistance = true;
  InstrumentMethod Instrument = InstrumentMethod::Automatic;
  /// How far the whole instrument is searched; 0: the engine's range.
  double InstrumentRangeMm = 0.0;
  /// The instrument's penetration depth and volume in each class, with the surface distance.
  bool ComputePenetration = true;
  /// The penetration walk's most vessel-wall queries per class and frame (0: no limit).
  long long PenetrationQueryBudget = vtkScalpelPenetration::DefaultQueryBudget;
  /// Thresholds, hysteresis and frame budget.
  TrackingSettings Tracking;
};

/// Refuses a vessel class that is one or two letters from a class of the default label table
/// ("portal_vien"): ParameterError("Vessels", "... did you mean 'portal_vein'?"). A misspelt class
/// would otherwise be a class of its own, and the vessel it meant would be missing from the
/// answers without a word.
void CheckVesselClassNames(const std::vector<NamedMesh>& vessels);

/// What opening a scene read and decided, for the front end to say and to report.
struct OpenedScene
{
  /// The vessels as read (and repaired), with their files: for the surface sections of reports
  /// and DescribeSurfaceDefects.
  std::vector<NamedMesh> Vessels;
  /// The tumours as read, with their files.
  std::vector<NamedMesh> Tumours;
  /// The liver surface, when one was asked for.
  vtkSmartPointer<vtkPolyData> Liver;
  /// Why method auto answers with the exact engine (no Vulkan device); empty otherwise.
  std::string EngineNote;
  /// The instrument's penetration is wanted but its surface is not closed, so its depth and
  /// volume cannot be known (they are left empty).
  bool PenetrationUnknown = false;
};
} // namespace vp

#endif
