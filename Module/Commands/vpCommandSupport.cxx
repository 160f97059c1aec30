#include "vpCommandSupport.h"

#include "vpEngineOptions.h"
#include "vtkScalpelModel.h"
#include "vtkVesselProximityLogic.h"

#include <vtkCallbackCommand.h>
#include <vtkNew.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace vp
{
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes)
{
  for (const std::string& line : DescribeSurfaceDefects(engine, meshes, "--repair"))
  {
    std::cerr << command << ": " << line << "\n";
  }
}

void ReportOpenedScene(
  const std::string& command, vtkVesselProximityLogic* proximity, const OpenedScene& scene, const std::string& scalpelFile)
{
  ReportEngineNote(scene.EngineNote);
  std::cerr << command << ": " << proximity->GetScalpel()->GetTipSource() << "\n";
  ReportSurfaceDefects(command, proximity->GetDistanceEngine(), scene.Vessels);
  for (const std::string& line : DescribeTumourDefects(scene.Tumours))
  {
    std::cerr << command << ": " << line << "\n";
  }
  if (scene.PenetrationUnknown)
  {
    std::cerr << command << ": " << scalpelFile
              << ": the surface is not closed, so the instrument's penetration depth and volume cannot be known (left empty)\n";
  }
}

StageProgress::StageProgress(std::string command, vtkVesselProximityLogic* logic)
  : Command(std::move(command))
  , Terminal(isatty(STDERR_FILENO) == 1)
  , Logic(logic)
{
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(this);
  observer->SetCallback([](vtkObject*, unsigned long, void* self, void* stage) {
    static_cast<StageProgress*>(self)->Stage(static_cast<const char*>(stage));
  });
  this->Tag = logic->AddObserver(vtkVesselProximityLogic::StageStartedEvent, observer);
}

StageProgress::~StageProgress()
{
  this->Logic->RemoveObserver(this->Tag);
  if (this->Terminal && this->Dirty)
  {
    std::fprintf(stderr, "\r\033[K"); // a refusal's line, or the summary, starts on a clean line
  }
}

void StageProgress::Stage(const std::string& name)
{
  this->EndStage();
  this->Current = name;
  this->StartedMs = NowMs();
  if (this->Terminal)
  {
    std::fprintf(stderr, "\r\033[K%s: %s", this->Command.c_str(), name.c_str());
    this->Dirty = true;
  }
}

void StageProgress::FramesDone(std::size_t done, std::size_t expected)
{
  if (this->Current != "frames")
  {
    this->Finish(); // the stages before the frames succeeded: their lines may be said
    this->Stage("frames");
  }
  const double share = expected > 0 ? static_cast<double>(done) / static_cast<double>(expected) : 0.0;
  if (this->Terminal)
  {
    const int width = 30, filled = static_cast<int>(std::lround(share * width));
    std::fprintf(stderr, "\r\033[K%s: frames [%s%s] %3.0f%% %zu/%zu", this->Command.c_str(), std::string(filled, '#').c_str(),
      std::string(width - filled, '.').c_str(), 100.0 * share, done, expected);
    this->Dirty = true;
  }
  else
  {
    std::fprintf(stderr, "%s: frame %zu of %zu (%.0f%%)\n", this->Command.c_str(), done, expected, 100.0 * share);
  }
}

void StageProgress::EndStage()
{
  if (this->Current.empty())
  {
    return;
  }
  const double seconds = (NowMs() - this->StartedMs) / 1000.0;
  if (this->Terminal)
  {
    std::fprintf(stderr, "\r\033[K");
    this->Dirty = false;
  }
  else if (seconds > 1.0 && this->Current != "frames")
  {
    char line[256];
    std::snprintf(line, sizeof line, "%s: %s: %.1f s\n", this->Command.c_str(), this->Current.c_str(), seconds);
    this->Pending.push_back(line);
  }
  this->Current.clear();
}

void StageProgress::Finish()
{
  this->EndStage();
  for (const std::string& line : this->Pending)
  {
    std::fputs(line.c_str(), stderr);
  }
  this->Pending.clear();
}
} // namespace vp
