// vesselproximity view: the module's 3D view in a window. The scalpel moves with the mouse and
// the keyboard, or replays recorded poses; the overlays follow every move.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpDangerLevels.h"
#include "vpDefaultScalpel.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpPoseFile.h"
#include "vpScalpelLoader.h"
#include "vpTrackingOptions.h"
#include "vpVirtualDisplay.h"
#include "vtkScalpelModel.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityView.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cstdlib>
#include <iostream>

namespace vp
{
namespace
{
const char* Usage =
  "usage: vesselproximity view --vessels CLASS=FILE[,CLASS=FILE...] [--scalpel FILE.stl [--tip X,Y,Z] [--axis X,Y,Z]]\n"
  "         [--poses FILE] [--pose N] [--liver FILE] [--method exact|zbuffer] [--danger-mm C,W,D] [--no-surface]\n"
  "         [--size WxH] [--keys K,K,...] [--screenshot FILE.png] [--frame-budget-ms MS]\n"
  "         [--hysteresis-mm MM] [engine options]\n"
  "  Opens the 3D view: vessels coloured by class, the scalpel coloured by danger level, a line to\n"
  "  the closest vessel point, a readout per class and the distance over time; a frame that took\n"
  "  longer than --frame-budget-ms (default 16.7, 60 Hz; 0: none) says so under the readout.\n"
  "  --hysteresis-mm: a level is left only this far past its threshold (default 0.3; 0: none).\n"
  "  --scalpel: default the built-in CUSA handpiece. Without --poses it starts 30 mm anterior of\n"
  "    the vessels' centre, pointing posterior (into the patient).\n"
  "  --poses: recorded poses to replay (space plays, n/b step); --pose N shows pose N first.\n"
  "  --keys: keys pressed before the window opens (VTK key names: Left, Up, Prior, i, n, ...).\n"
  "  --screenshot: render off-screen, save the PNG and exit (no window; Xvfb is started when\n"
  "    there is no display).\n";

std::pair<int, int> ParseSize(const std::string& text)
{
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 64 || h < 64 || w > 8192 || h > 8192)
  {
    throw InputError("--size", "expected WIDTHxHEIGHT in pixels (64..8192), got '" + text + "'");
  }
  return { w, h };
}

std::vector<std::string> SplitKeys(const std::string& text)
{
  std::vector<std::string> keys;
  for (const std::string& key : SplitList(text, ','))
  {
    if (!key.empty())
    {
      keys.push_back(key);
    }
  }
  return keys;
}

/// Tip 30 mm anterior (-y in LPS) of the vessels' centre, the model's +z axis turned to +y: the
/// scalpel points into the patient from the front.
std::array<double, 16> StartingPose(vtkVesselProximityLogic* logic)
{
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  logic->GetVesselBounds(bounds);
  const double cx = 0.5 * (bounds[0] + bounds[1]), cy = bounds[2] - 30.0, cz = 0.5 * (bounds[4] + bounds[5]);
  return { 1, 0, 0, cx, 0, 0, 1, cy, 0, -1, 0, cz, 0, 0, 0, 1 };
}
Arguments ParseViewArguments(const std::vector<std::string>& argv)
{
  std::set<std::string> options = EngineValueOptions();
  options.insert({ "--vessels", "--scalpel", "--tip", "--axis", "--poses", "--pose", "--liver", "--danger-mm", "--size",
    "--keys", "--screenshot", "--frame-budget-ms", "--hysteresis-mm" });
  Arguments args(argv, options, { "--no-surface" });
  if (!args.Positional().empty())
  {
    throw InputError(args.Positional()[0], "unexpected argument (see vesselproximity view --help)");
  }
  if (!args.Has("--vessels"))
  {
    throw InputError("--vessels", "is required (see vesselproximity view --help)");
  }
  const std::string method = args.Get("--method", "exact");
  if (method != "exact" && method != "zbuffer")
  {
    throw InputError("--method", "expected exact or zbuffer for the view, got '" + method + "'");
  }
  return args;
}

/// The vessels, the scalpel (the built-in handpiece unless one is given) and the liver.
vtkSmartPointer<vtkPolyData> ReadScene(const Arguments& args, const ScalpelTipDefinition& tip, vtkVesselProximityLogic* logic)
{
  for (const auto& m : LoadVesselMeshes(ParsePairs(args.Get("--vessels"), "--vessels")))
  {
    logic->AddVessel(m.ClassName, m.Mesh);
  }
  vtkSmartPointer<vtkPolyData> liver;
  if (args.Has("--liver"))
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(args.Get("--liver"));
    reader->Read();
    liver = reader->GetOutput();
  }
  logic->SetScalpel(args.Has("--scalpel") ? LoadScalpel(args.Get("--scalpel"), tip) : MakeDefaultScalpel(tip));
  logic->Build();
  return liver;
}

/// A window needs the user's display; a screenshot takes a virtual one when there is none.
void RequireDisplay(const std::string& screenshot, VirtualDisplay& display)
{
  const char* displayName = std::getenv("DISPLAY");
  if (screenshot.empty() && !(displayName && *displayName))
  {
    throw InputError("view", "no display to open a window on (DISPLAY is unset); use --screenshot for an image");
  }
  if (!screenshot.empty() && !display.Ensure())
  {
    throw InputError("--screenshot", display.GetProblem());
  }
}

void PrintScreenshotLine(const std::string& screenshot, vtkVesselProximityLogic* logic)
{
  const vp::TrackedFrame& f = logic->GetLastFrame();
  const int nearest = f.Proximity.NearestIndex();
  std::cout << "wrote " << screenshot << ": tip " << f.TipMm[0] << ", " << f.TipMm[1] << ", " << f.TipMm[2] << " mm, level "
            << DangerLevelName(f.Level);
  if (nearest >= 0)
  {
    std::cout << ", nearest " << f.Proximity.Classes[nearest].ClassName << " " << f.Proximity.Classes[nearest].DistanceMm << " mm";
  }
  std::cout << "\n";
}
} // namespace

int RunViewCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << Usage << EngineOptionsUsage({ "exact", "zbuffer" }) << vtkVesselProximityView::KeyHelp();
    return 0;
  }
  const Arguments args = ParseViewArguments(argv);
  const ScalpelTipDefinition tip = ParseTipDefinition(args);
  const auto size = ParseSize(args.Get("--size", "1280x800"));
  const std::vector<std::string> keys = SplitKeys(args.Get("--keys"));
  const std::string screenshot = args.Get("--screenshot");
  vtkSmartPointer<vtkVesselProximityLogic> logic = ConfigureTrackingLogic(args, args.Get("--method", "exact"));
  // Everything that can be refused is read before a window opens.
  std::vector<TrackedPose> poses;
  if (args.Has("--poses"))
  {
    poses = ReadPoseFile(args.Get("--poses"));
  }
  const int first = args.GetInteger("--pose", 0);
  if (args.Has("--pose") && (first < 0 || first >= static_cast<int>(poses.size())))
  {
    throw InputError("--pose", "no pose " + std::to_string(first) + " (the pose file has " + std::to_string(poses.size()) + ")");
  }
  vtkSmartPointer<vtkPolyData> liver = ReadScene(args, tip, logic);
  VirtualDisplay display;
  RequireDisplay(screenshot, display);
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(!screenshot.empty());
  view->SetSizePx(size.first, size.second);
  view->SetLogic(logic);
  if (liver)
  {
    view->SetLiverSurface(liver);
  }
  view->SetPoses(poses);
  for (int i = 0; i <= first && !poses.empty(); ++i)
  {
    view->ShowPose(i); // the plot shows the way there
  }
  if (poses.empty())
  {
    view->SetScalpelPose(StartingPose(logic));
  }
  view->PressKeys(keys);
  if (!screenshot.empty())
  {
    view->SaveScreenshot(screenshot);
    PrintScreenshotLine(screenshot, logic);
    return 0;
  }
  std::cout << vtkVesselProximityView::KeyHelp();
  view->Start();
  return 0;
}
} // namespace vp
