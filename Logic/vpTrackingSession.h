#ifndef vpTrackingSession_h
#define vpTrackingSession_h

#include "vpFrameOutput.h"
#include "vpPoseFile.h"
#include "vpTrackedFrame.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <functional>
#include <vector>

class vtkCallbackCommand;

class vtkVesselProximityLogic;

namespace vp
{
/// One run of poses through the module logic: the frame loop every front end shares. A file, a
/// list, a live stream and the viewer's interactive moves are all poses of one session; the
/// logic (opened: vtkVesselProximityLogic::OpenScene) computes each frame, and the session hands
/// it, with the changes of level it made, to its outputs (vp::FrameOutput).
///
/// The session starts the logic's tracking afresh: its first pose is frame 0, from the safe level.
class TrackingSession
{
public:
  explicit TrackingSession(vtkVesselProximityLogic* logic);
  ~TrackingSession();
  TrackingSession(const TrackingSession&) = delete;
  TrackingSession& operator=(const TrackingSession&) = delete;

  /// An output told of every frame, change of level, lost pose and the end from now on (not
  /// owned: it outlives the session's runs). Outputs hear in the order they were added.
  void AddOutput(FrameOutput* output);

  /// One pose: its frame, valid until the next pose; the outputs have been told of it.
  const TrackedFrame& Process(const TrackedPose& pose);
  /// A pose the tracker lost (TrackedPose::Lost): counted and told to the outputs, never
  /// computed (no distance comes from where the tool was before).
  void ProcessLost(const TrackedPose& pose);

  /// Every pose of the source in turn; each frame goes to the outputs, then to onFrame (may be
  /// empty), outside the frame's own time. A lost pose (the tracker did not see the tool) is
  /// counted and goes to the outputs and onLost (may be empty), never computed: no distance comes
  /// from where the tool was before. The outputs hear OnEnd when the run ends, by its source
  /// or by a signal (not when it throws).
  /// Returns false when a held signal came (RunFolder::SignalPending) before the source ended,
  /// unless the signal is the source's own end (PoseSource::EndsOnSignal): the caller lets its
  /// RunFolder go and the signal acts. Throws the source's InputError.
  bool Run(PoseSource& poses, const std::function<void(const TrackedFrame&)>& onFrame = {},
    const std::function<void(const TrackedPose&)>& onLost = {});

  /// Called about once a second during Run with the poses done and the source's expected count.
  void SetProgress(std::function<void(std::size_t done, std::size_t expected)> progress);

  /// Starts over: the next pose is frame 0, from the safe level.
  void Restart();

  /// Frames computed since the session started (or restarted).
  std::size_t GetNumberOfFrames() const { return this->Frames; }
  /// Poses the tracker had lost (from Run or ProcessLost), and the time of the first (s).
  std::size_t GetNumberOfLostPoses() const { return this->Lost; }
  double GetFirstLostTimeS() const { return this->FirstLostTimeS; }
  vtkVesselProximityLogic* GetLogic() const { return this->Logic.GetPointer(); }

private:
  void Deliver(const TrackedFrame& frame);

  vtkSmartPointer<vtkVesselProximityLogic> Logic; // held: the session observes its tracking logic
  std::vector<FrameOutput*> Outputs;
  /// The tracking logic's changes of level during the frame being computed, handed to the
  /// outputs once it is (the logic announces them inside its ProcessPose).
  std::vector<DangerLevelChange> PendingChanges;
  std::vector<MarginLevelChange> PendingMarginChanges;
  vtkNew<vtkCallbackCommand> OnChange;
  vtkNew<vtkCallbackCommand> OnMarginChange;
  unsigned long ObserverTags[2] = { 0, 0 };
  std::function<void(std::size_t, std::size_t)> Progress;
  std::size_t Frames = 0;
  std::size_t Lost = 0;
  double FirstLostTimeS = 0.0;
};
} // namespace vp

#endif
