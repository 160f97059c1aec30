#ifndef vpCommandSupport_h
#define vpCommandSupport_h

#include "vpClock.h"
#include "vpQuantile.h"
#include "vpRunFolder.h" // CreateOutputFolder
#include "vpSceneRequest.h"
#include "vpSurfaceReport.h"
#include "vpVesselMeshSet.h"

#include <string>
#include <vector>

class vtkVesselDistanceEngine;
class vtkVesselProximityLogic;

namespace vp
{
/// DescribeSurfaceDefects on stderr, a line each prefixed with the command's name: after the
/// engine's Build(), so that no line comes before a refusal.
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);

/// What an opened scene tells the user (the engine's note, where the tip came from, the surfaces'
/// defects, a penetration that cannot be known), on stderr: said once everything is built and
/// checked, since a line before a refusal would make its one line two.
void ReportOpenedScene(
  const std::string& command, vtkVesselProximityLogic* proximity, const OpenedScene& scene, const std::string& scalpelFile);
/// Progress on stderr for a command's long stages: the logic's stages of opening the scene
/// (vtkVesselProximityLogic::StageStartedEvent) and the frames (FramesDone). On a terminal, one
/// line rewritten in place ("track: building the exact engine", then a bar "track: frames
/// [#####.....] 52% 477/918"), cleared when it is destroyed, so that a refusal's one line stands
/// alone; otherwise plain lines, and only for what took over a second: a stage's line
/// ("track: building the exact engine: 1.4 s") once the stages so far have succeeded (Finish(),
/// so that a refusal's one line stands alone there too), the frames' each second.
class StageProgress
{
public:
  StageProgress(std::string command, vtkVesselProximityLogic* logic);
  ~StageProgress();
  StageProgress(const StageProgress&) = delete;
  StageProgress& operator=(const StageProgress&) = delete;
  /// The stage now starting (also called by the logic's events).
  void Stage(const std::string& name);
  /// The frames so far (called once a second at most by the session).
  void FramesDone(std::size_t done, std::size_t expected);
  /// Ends the current stage and says, in a log, the stages so far that took over a second (a
  /// terminal's line is cleared). Call once they succeeded.
  void Finish();

private:
  void EndStage();
  std::vector<std::string> Pending; ///< a log's stage lines, said by Finish()
  std::string Command, Current;
  double StartedMs = 0.0;
  bool Terminal = false, Dirty = false;
  vtkVesselProximityLogic* Logic = nullptr;
  unsigned long Tag = 0;
};
} // namespace vp

#endif
