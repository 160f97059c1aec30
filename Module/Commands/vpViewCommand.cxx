// vesselproximity view: the module's 3D view in a window. The scalpel moves with the mouse and
// the keyboard, or replays recorded poses; the overlays follow every move.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpDangerLevels.h"
#include "vpEngineOptions.h"
#include "vpFrameHeadline.h"
#include "vpIgtlLink.h"
#include "vpInputError.h"
#include "vpLiveOptions.h"
#include "vpOutputOptions.h"
#include "vpLivePoseSource.h"
#include "vpPointCsv.h"
#include "vpPoseFile.h"
#include "vpSignalHold.h"
#include "vpTrackingOptions.h"
#include "vpVirtualDisplay.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityView.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>

namespace vp
{
namespace
{
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

/// The view's key help as the command's help lists it: each line kept as written.
std::string KeysAsListed()
{
  std::string listed;
  for (const std::string& line : SplitList(vtkVesselProximityView::KeyHelp(), '\n'))
  {
    listed += line.empty() ? "" : "  " + line + "\n";
  }
  return listed;
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
  std::cout << "wrote " << screenshot << ": tip " << f.TipMm[0] << ", " << f.TipMm[1] << ", " << f.TipMm[2] << " mm; "
            << FrameHeadline(f) << " (" << logic->GetTrackingLogic()->GetDistanceEngine()->GetMethodName() << " engine"
            << (f.Proximity.ErrorBoundMm > 0.0 ? ", within " + FixedText(f.Proximity.ErrorBoundMm, "%.2f") + " mm" : "") << ")\n";
}
/// What view reads, and refuses, before a window opens.
struct ViewInputs
{
  std::vector<TrackedPose> Poses;
  int FirstPose = 0;
  std::optional<IgtlLinkSettings> Stream;
  double StaleMs = 0.0;
  double DurationS = 0.0;
  std::pair<int, int> SizePx;
  std::vector<std::string> Keys;
  std::string Screenshot;
  vtkVesselProximityView::CameraPreset Camera = vtkVesselProximityView::CameraPreset::Anterior;
};

ViewInputs ReadViewInputs(const cli::ParsedArguments& args)
{
  ViewInputs in;
  in.SizePx = ParseSize(args.GetString("size"));
  in.Keys = SplitKeys(args.GetString("keys"));
  in.Screenshot = args.GetString("screenshot");
  vtkVesselProximityView::ParseCameraPreset(args.GetString("view"), in.Camera); // an enumeration: checked by the parser
  if (args.IsSet("poses"))
  {
    in.Poses = ReadPoseFile(args.GetString("poses"), ParsePoseReading(args));
  }
  if (WantsLiveStream(args))
  {
    if (args.IsSet("poses"))
    {
      throw InputError("--poses/--igtl", "give recorded poses or a live stream, not both");
    }
    in.Stream = ParseLiveStream(args);
    in.StaleMs = ParseStaleMs(args);
    in.DurationS = ParseDurationS(args);
    if (!in.Screenshot.empty() && in.DurationS <= 0.0)
    {
      throw InputError("--duration-s", "say how long to follow the stream before the screenshot");
    }
  }
  in.FirstPose = args.IsSet("pose") ? args.GetInteger("pose") : 0;
  if (args.IsSet("pose") && in.FirstPose >= static_cast<int>(in.Poses.size()))
  {
    throw InputError("--pose", "no pose " + std::to_string(in.FirstPose) + " (the pose file has " + std::to_string(in.Poses.size()) + ")");
  }
  return in;
}

/// The window on the logic, at its first pose (the plot showing the way there) or at the
/// starting pose, the keys pressed; every frame it computes goes to the outputs.
void SetUpView(vtkVesselProximityView* view, const ModuleServices& module, vtkVesselProximityLogic* logic,
  const OpenedScene& scene, const ViewInputs& in, const std::vector<FrameOutput*>& outputs)
{
  view->SetOverlays(module.CreateWidgetRepresentation());
  view->SetOffScreen(!in.Screenshot.empty());
  view->SetSizePx(in.SizePx.first, in.SizePx.second);
  view->SetLogic(logic);
  for (FrameOutput* output : outputs)
  {
    view->AddOutput(output);
  }
  view->SetCameraPreset(in.Camera);
  if (scene.Liver)
  {
    view->SetLiverSurface(scene.Liver);
  }
  view->SetPoses(in.Poses);
  if (!in.Poses.empty())
  {
    view->ReplayTo(in.FirstPose);
  }
  else
  {
    view->SetScalpelPose(StartingPose(logic));
  }
  view->PressKeys(in.Keys);
}

/// The live stream the inputs ask for, followed by the view (none without one).
void OpenViewStream(vtkVesselProximityView* view, const ViewInputs& in, std::unique_ptr<IgtlLink>& link,
  std::unique_ptr<LivePoseSource>& source)
{
  if (!in.Stream)
  {
    return;
  }
  link = std::make_unique<IgtlLink>(*in.Stream);
  source = std::make_unique<LivePoseSource>(*link, in.Stream->ToolName, in.StaleMs, in.DurationS);
  IgtlLink* events = link.get();
  source->SetIdleCallback([events] { PrintLinkEvents("view", *events); });
  view->SetLiveSource(source.get());
  if (link->GetListenPort() >= 0)
  {
    std::cerr << "view: listening on port " << link->GetListenPort() << "\n";
  }
}

/// The stream followed for its duration, then the screenshot and what it shows.
void ShootLiveView(vtkVesselProximityView* view, vtkVesselProximityLogic* logic, const ViewInputs& in)
{
  view->FollowLiveFor(in.DurationS);
  SignalHold::Answer();
  view->SaveScreenshot(in.Screenshot);
  if (view->GetTrackingLost())
  {
    std::cout << "wrote " << in.Screenshot << ": tracking lost at the end (the last frame, " << logic->GetLastFrame().TimeS
              << " s, is not shown as current)\n";
  }
  else
  {
    PrintScreenshotLine(in.Screenshot, logic);
  }
  std::cout << (view->GetTrackingLost() ? "tracking lost: no distance shown as current\n" : "tracking\n");
}
} // namespace


cli::ModuleDescription DescribeViewCommand()
{
  using cli::ParameterType;
  std::vector<cli::Parameter> scene = {
    VesselsOption().SetRequired(),
    Option(ParameterType::File, "scalpel", "The scalpel's surface model (default: the built-in CUSA handpiece).")
      .SetChannel(cli::Channel::Input),
  };
  for (const cli::Parameter& p : ScalpelTipOptions())
  {
    scene.push_back(p);
  }
  scene.push_back(Option(ParameterType::File, "liver", "A liver surface, shown translucent.").SetChannel(cli::Channel::Input));
  return cli::ModuleDescription::Subcommand("vesselproximity view",
    "interactive window: vessels, scalpel moved by mouse and keys or replayed, live overlays",
    "Opens the 3D view: vessels coloured by class, the scalpel coloured by danger level, a line to the closest vessel "
    "point, a readout per class and the distance over time; a frame that took longer than the frame budget says so "
    "under the readout. Without --poses the scalpel starts 30 mm anterior of the vessels' centre, pointing "
    "posterior (into the patient).\n" + KeysAsListed(),
    {
      { "Scene", "", scene },
      { "Replay and window", "",
        {
          Option(ParameterType::File, "poses", "Recorded poses to replay (space plays, n/b step).").SetChannel(cli::Channel::Input),
          PoseReadingOptions()[0],
          PoseReadingOptions()[1],
          PoseReadingOptions()[2],
          PoseReadingOptions()[3],
          PoseReadingOptions()[4],
          PoseReadingOptions()[5],
          Option(ParameterType::Integer, "pose", "The pose shown first, from 0.").SetPlaceholder("N").SetRange(0, 1000000000, 1),
          Option(ParameterType::String, "size", "The window's size in pixels (64..8192 each).").SetPlaceholder("WxH").SetDefault("1280x800"),
          Option(ParameterType::StringEnumeration, "view",
            "Where the camera looks from (the world is LPS): anterior (superior up, as Slicer's 3D view), lateral (from the "
            "patient's right), superior (from above, anterior up), tool (beside the scalpel, the tip in the middle, every frame), "
            "follow (the camera moves with the tip) or clear (beside the tool, turned until the tip and the nearest vessel's "
            "closest point are both in plain sight, checked on the rendered depth, every frame). A cube in the lower left "
            "corner names the patient's directions.")
            .SetDefault("anterior")
            .SetElements({ "anterior", "lateral", "superior", "tool", "follow", "clear" }),
          Option(ParameterType::String, "keys", "Keys pressed before the window opens (VTK key names: Left, Up, Prior, i, n, ...).")
            .SetPlaceholder("K,K,..."),
          Option(ParameterType::File, "screenshot",
            "Render off-screen, save the PNG and exit (no window; Xvfb is started when there is no display).")
            .SetChannel(cli::Channel::Output)
            .SetPlaceholder("FILE.png"),
        } },
      { "Live stream", "", LiveStreamOptions(false, false) },
      EngineOptions(EngineMethodNames(OfferedInView)),
      TrackingOptions(),
      OutputOptions(OutputForView),
    });
}

int RunViewCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  // A live view ends at Ctrl-C: held, then answered once the window is closed.
  std::optional<SignalHold> hold;
  if (WantsLiveStream(args))
  {
    hold.emplace();
  }
  SceneRequest request = ParseSceneRequest(args);
  request.LiverFile = args.GetString("liver");
  const ViewInputs in = ReadViewInputs(args); // everything that can be refused, before a window opens
  std::vector<std::string> inputs = SceneInputFiles(request);
  inputs.push_back(args.GetString("poses"));
  const ChosenOutputs chosen(args, OutputForView, "view", inputs);
  vtkSmartPointer<vtkVesselProximityLogic> logic = module.CreateLogic();
  OpenedScene scene;
  {
    StageProgress progress("view", logic); // a window or a stream waits on these: say what they are
    scene = logic->OpenScene(request);
  }
  ReportEngineNote(scene.EngineNote);
  TrackingSummary frames; // every frame the window shows, for the frame times said when it closes
  const double budgetMs = logic->GetTrackingLogic()->GetFrameBudgetMs();
  VirtualDisplay display;
  RequireDisplay(in.Screenshot, display);
  vtkNew<vtkVesselProximityView> view;
  std::vector<FrameOutput*> outputs = { &frames };
  outputs.insert(outputs.end(), chosen.Get().begin(), chosen.Get().end());
  SetUpView(view, module, logic, scene, in, outputs);
  // The stream opens once the window is ready: no pose waits on a build.
  std::unique_ptr<IgtlLink> link;
  std::unique_ptr<LivePoseSource> source;
  OpenViewStream(view, in, link, source);
  if (!in.Screenshot.empty() && source)
  {
    ShootLiveView(view, logic, in);
  }
  else if (!in.Screenshot.empty())
  {
    view->SaveScreenshot(in.Screenshot);
    PrintScreenshotLine(in.Screenshot, logic);
  }
  else
  {
    std::cout << vtkVesselProximityView::KeyHelp();
    view->Start();
    SignalHold::Answer(); // a live session's Ctrl-C ended it
  }
  std::cout << FrameTimesText(frames, budgetMs) << "\n";
  chosen.SayProblems();
  return 0;
}
} // namespace vp
