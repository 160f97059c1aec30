#include "vpCohortCase.h"

#include "vpClock.h"
#include "vpDistanceEngineFactory.h"
#include "vpInputError.h"
#include "vpOutputFile.h"
#include "vpPointCsv.h"
#include "vpRunFolder.h"
#include "vpSceneRequest.h"
#include "vpTipDistanceQuery.h"
#include "vpTrackingRecorder.h"
#include "vtkVesselProximityLogic.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

/// FNV-1a, 64 bits, over a file's bytes: a change to what a file holds, not only to its size or
/// time, is seen (masks replaced in place with the same names and sizes); "" when unreadable.
std::string ContentHash(const std::filesystem::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
  {
    return std::string();
  }
  std::uint64_t h = 14695981039346656037ull;
  std::vector<char> chunk(1 << 16);
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
  {
    for (std::streamsize i = 0; i < in.gcount(); ++i)
    {
      h = (h ^ static_cast<unsigned char>(chunk[static_cast<std::size_t>(i)])) * 1099511628211ull;
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

/// A regular file's identity: its size, time and content hash.
Json FileJson(const std::filesystem::path& file)
{
  std::error_code error;
  const auto bytes = std::filesystem::file_size(file, error);
  const auto modified = std::filesystem::last_write_time(file, error).time_since_epoch().count();
  return { { "bytes", error ? Json(nullptr) : Json(bytes) }, { "modified", static_cast<long long>(modified) },
    { "hash", ContentHash(file) } };
}

/// Every regular file under a folder, by its path from there, sorted.
std::vector<std::string> FilesUnder(const std::filesystem::path& folder)
{
  std::vector<std::string> names;
  std::error_code error;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, error); !error && it != std::filesystem::recursive_directory_iterator();
       it.increment(error))
  {
    if (it->is_regular_file(error))
    {
      names.push_back(std::filesystem::relative(it->path(), folder, error).string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// An input's identity for a later run: its path and, for a file, its size, time and content
/// hash; for a folder (a DICOM series), each file inside it so.
Json InputJson(const std::string& path)
{
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
  {
    return { { "path", path }, { "missing", true } };
  }
  if (!std::filesystem::is_directory(status))
  {
    Json entry = FileJson(path);
    entry["path"] = path;
    return entry;
  }
  Json files = Json::object();
  for (const std::string& name : FilesUnder(path))
  {
    files[name] = FileJson(std::filesystem::path(path) / name);
  }
  return { { "path", path }, { "files", files } };
}

/// What a case's run wrote, each file by its path in the case's folder (case.json aside): size
/// and content hash, so that a resume takes a case only while its files are as written.
Json OutputsJson(RunFolder& run)
{
  Json outputs = Json::object();
  const std::vector<std::string> entries = run.GetEntries(); // a copy: File() and Folder() add to it
  for (const std::string& entry : entries)
  {
    const bool folder = !entry.empty() && entry.back() == '/';
    const std::string name = folder ? entry.substr(0, entry.size() - 1) : entry;
    if (name == "case.json")
    {
      continue;
    }
    const std::filesystem::path staged = folder ? run.Folder(name) : run.File(name);
    for (const std::string& inside : folder ? FilesUnder(staged) : std::vector<std::string>{ "" })
    {
      const std::filesystem::path file = inside.empty() ? staged : staged / inside;
      const Json id = FileJson(file);
      outputs[inside.empty() ? name : name + "/" + inside] = { { "bytes", id["bytes"] }, { "hash", id["hash"] } };
    }
  }
  return outputs;
}

/// Why a case's folder no longer holds what its run wrote ("" when it does).
std::string OutputsChanged(const nlohmann::json& recorded, const std::string& folder)
{
  for (const auto& [name, id] : recorded.items())
  {
    const std::filesystem::path file = std::filesystem::path(folder) / name;
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error))
    {
      return name + " is gone";
    }
    const Json now = FileJson(file);
    if (now["bytes"].dump() != id.at("bytes").dump() || now["hash"].dump() != id.at("hash").dump())
    {
      return name + " changed since it was written";
    }
  }
  return std::string();
}

Json OptionalJson(const std::optional<double>& value)
{
  return value ? Json(*value) : Json(nullptr);
}

std::optional<double> OptionalOf(const nlohmann::json& value)
{
  return value.is_number() ? std::optional<double>(value.get<double>()) : std::nullopt;
}

void Lower(std::optional<double>& current, double value)
{
  current = current ? std::min(*current, value) : value;
}

CohortClassRow& RowOf(std::vector<CohortClassRow>& rows, const std::string& className)
{
  const auto it = std::find_if(rows.begin(), rows.end(), [&](const CohortClassRow& r) { return r.ClassName == className; });
  if (it != rows.end())
  {
    return *it;
  }
  rows.push_back({ className, std::nullopt, std::nullopt, std::nullopt, 0 });
  return rows.back();
}

/// Stops the case when a held signal came: the folder is left as it was.
struct Interrupted
{
};

void CheckSignal()
{
  if (RunFolder::SignalPending())
  {
    throw Interrupted();
  }
}
} // namespace

Json CohortCaseInputsJson(const CohortCase& c)
{
  Json plan = Json::array();
  for (const NamedMesh& tumour : TumourEntries(c.Plan, "plan"))
  {
    Json entry = InputJson(tumour.FileName);
    entry["id"] = tumour.ClassName;
    plan.push_back(entry);
  }
  const PoseReading& r = c.Reading;
  const Json reading = { { "pose_space", r.Space ? Json(PoseSpaceName(*r.Space)) : Json(nullptr) },
    { "mm_per_unit", r.MillimetresPerUnit ? Json(*r.MillimetresPerUnit) : Json(nullptr) },
    { "s_per_unit", r.SecondsPerUnit ? Json(*r.SecondsPerUnit) : Json(nullptr) }, { "tool", r.ToolName },
    { "reference", r.ReferenceName } };
  return { { "segmentation", InputJson(c.Segmentation) }, { "poses", c.Poses.empty() ? Json(nullptr) : InputJson(c.Poses) },
    { "pose_reading", reading },
    { "tips", c.Tips.empty() ? Json(nullptr) : InputJson(c.Tips) }, { "plan", plan },
    { "scalpel", c.Scalpel.empty() ? Json(nullptr) : InputJson(c.Scalpel) } };
}

namespace
{
/// The track stage: the case's poses through the module's logic into the run folder, its rows'
/// closest approaches, penetrations, breaches and the smallest margin taken from the summary.
void TrackCohortCase(const CohortCase& c, const std::vector<NamedMesh>& vessels, const std::vector<NamedMesh>& tumours,
  const CohortLogicFactory& makeLogic, RunFolder& run, CohortCaseResult& result)
{
  SceneRequest request;
  request.Vessels = vessels;
  request.Tumours = tumours;
  request.ScalpelFile = c.Scalpel;
  vtkSmartPointer<vtkVesselProximityLogic> logic = makeLogic ? makeLogic() : vtkSmartPointer<vtkVesselProximityLogic>::New();
  const OpenedScene scene = logic->OpenScene(request);
  TrackingRecorder recorder(logic, scene.Vessels);
  PoseStream poses(c.Poses, PoseStream::CountPoses(c.Poses, c.Reading), c.Reading);
  if (!recorder.Run(poses, run))
  {
    throw Interrupted();
  }
  const TrackingSummary& s = recorder.GetSummary();
  result.Frames = s.GetNumberOfFrames();
  for (std::size_t k = 0; k < s.GetClassNames().size(); ++k)
  {
    CohortClassRow& row = RowOf(result.Classes, s.GetClassNames()[k]);
    const ClassMinimum& tip = s.GetTipMinimum()[k];
    if (tip.Seen)
    {
      Lower(row.TipMinMm, tip.Inside ? -tip.DistanceMm : tip.DistanceMm);
    }
    if (k < s.GetSurfaceMinimum().size() && s.GetSurfaceMinimum()[k].Seen)
    {
      Lower(row.SurfaceMinMm, s.GetSurfaceMinimum()[k].DistanceMm);
    }
    if (k < s.GetPenetrationMaximum().size() && s.GetPenetrationMaximum()[k].Known)
    {
      row.PenetrationMaxMm3 = s.GetPenetrationMaximum()[k].VolumeMm3;
      if (s.GetPenetrationMaximum()[k].DepthFrame >= 0)
      {
        row.PenetrationDepthMaxMm = s.GetPenetrationMaximum()[k].DepthMm;
      }
    }
    row.BreachFrames = s.GetFramesInBreach()[k];
  }
  for (const TumourMarginSummary& t : s.GetTumours())
  {
    Lower(result.MarginMinMm, t.MarginMinMm);
    result.Tumours.push_back({ t.Id, t.MarginMinMm, t.SurfaceSeen ? std::optional<double>(t.SurfaceMinMm) : std::nullopt });
  }
}

/// The tips stage: distance.json as `distance --json --tumour` writes it, and the rows' closest tips.
void TipsOfCohortCase(const CohortCase& c, const std::vector<NamedMesh>& vessels, const std::vector<NamedMesh>& tumours,
  RunFolder& run, CohortCaseResult& result)
{
  TipDistanceRequest request;
  request.Engine = MakeDistanceEngine(DistanceEngineSettings());
  request.Vessels = vessels;
  request.Tumours = LoadTumourMeshes(tumours); // as `distance --tumour`: each tip's signed distance beside the vessels
  request.TipsMm = ReadPointCsv(c.Tips);
  const TipDistanceAnswer answer = ComputeTipDistances(request);
  WriteFileAtomically(run.File("distance.json"), TipDistanceReportJson(request, answer, false, 0.0).dump(2) + "\n");
  result.Tips = static_cast<int>(request.TipsMm.size());
  for (const ProximityResult& r : answer.Results)
  {
    for (const ClassProximity& p : r.Classes)
    {
      if (p.InRange)
      {
        Lower(RowOf(result.Classes, p.ClassName).TipMinMm, p.Inside.value_or(false) ? -p.DistanceMm : p.DistanceMm);
      }
    }
  }
}

/// case.json: the inputs, the rows, the files written with their hashes, the stage times.
Json CaseRecord(const CohortCase& c, const CohortCaseResult& result, RunFolder& run, const Json& timing)
{
  Json classes = Json::array();
  for (const CohortClassRow& row : result.Classes)
  {
    classes.push_back({ { "class", row.ClassName }, { "tip_min_mm", OptionalJson(row.TipMinMm) },
      { "surface_min_mm", OptionalJson(row.SurfaceMinMm) }, { "penetration_max_mm3", OptionalJson(row.PenetrationMaxMm3) },
      { "breach_frames", row.BreachFrames }, { "penetration_depth_max_mm", OptionalJson(row.PenetrationDepthMaxMm) } });
  }
  Json tumours = Json::array();
  for (const CohortTumourRow& t : result.Tumours)
  {
    tumours.push_back({ { "id", t.Id }, { "margin_min_mm", OptionalJson(t.MarginMinMm) }, { "surface_min_mm", OptionalJson(t.SurfaceMinMm) } });
  }
  return { { "case", c.Name }, { "inputs", CohortCaseInputsJson(c) }, { "classes", classes }, { "tumours", tumours },
    { "margin_min_mm", OptionalJson(result.MarginMinMm) }, { "frames", result.Frames }, { "tips", result.Tips },
    { "files", run.GetEntries() }, { "outputs", OutputsJson(run) }, { "timing_ms", timing } };
}
} // namespace

CohortCaseResult RunCohortCase(const CohortCase& c, const std::string& folder, const CohortSettings& settings,
  const CohortLogicFactory& makeLogic, const CohortStageObserver& observer)
{
  CohortCaseResult result;
  result.Case = c.Name;
  const double start = NowMs();
  const auto stage = [&](const char* name) {
    CheckSignal();
    if (observer)
    {
      observer(c.Name, name);
    }
  };
  try
  {
    std::vector<NamedMesh> tumours = TumourEntries(c.Plan, c.Name + " plan");
    RunFolder run(folder, "case.json");
    std::vector<std::string> inputs = { c.Segmentation };
    for (const std::string& path : { c.Poses, c.Tips, c.Scalpel })
    {
      if (!path.empty())
      {
        inputs.push_back(path);
      }
    }
    for (const NamedMesh& tumour : tumours)
    {
      inputs.push_back(tumour.FileName);
    }
    run.SetInputs(inputs);
    run.Begin();
    Json timing;

    stage("models");
    double t0 = NowMs();
    const VesselModelSet models = BuildVesselModels({ c.Segmentation }, settings.Models, [](const std::string&, double) {});
    WriteVesselModelFiles(models, run.Folder("models"));
    std::vector<NamedMesh> vessels;
    const bool planned = !tumours.empty();
    for (const VesselClassModel& m : models.Models)
    {
      if (m.Role == ModelRole::Vessel) // the liver is shown beside the vessels, never measured
      {
        vessels.push_back({ m.ClassName, c.Segmentation, m.Surface, std::nullopt });
        RowOf(result.Classes, m.ClassName);
      }
      else if (m.Role == ModelRole::Tumour && !planned) // no plan: the segmentation's own tumours
      {
        tumours.push_back({ m.Name, c.Segmentation, m.Surface, std::nullopt });
      }
    }
    if (vessels.empty())
    {
      throw InputError(c.Segmentation, "no vessel class in it (only the liver)");
    }
    timing["models"] = NowMs() - t0;
    if (!c.Poses.empty())
    {
      stage("track");
      t0 = NowMs();
      TrackCohortCase(c, vessels, tumours, makeLogic, run, result);
      timing["track"] = NowMs() - t0;
    }
    if (!c.Tips.empty())
    {
      stage("tips");
      t0 = NowMs();
      TipsOfCohortCase(c, vessels, tumours, run, result);
      timing["tips"] = NowMs() - t0;
    }
    CheckSignal();
    result.Ms = NowMs() - start;
    timing["total"] = result.Ms;
    WriteFileAtomically(run.File("case.json"), CaseRecord(c, result, run, timing).dump(2) + "\n");
    run.Commit();
  }
  catch (const Interrupted&)
  {
    result.Error = "interrupted";
  }
  catch (const std::exception& e)
  {
    // One line: what a case's file or setting did wrong, the case's folder left as it was.
    std::string line = e.what();
    std::replace(line.begin(), line.end(), '\n', ' ');
    result.Error = line;
  }
  result.Ms = NowMs() - start;
  return result;
}

namespace
{
constexpr std::uintmax_t MaxCaseRecordBytes = 1u << 20;
} // namespace

std::optional<CohortCaseResult> CompletedCohortCase(const CohortCase& c, const std::string& folder, std::string* whyNot)
{
  const auto skip = [&](const std::string& why) -> std::optional<CohortCaseResult> {
    if (whyNot)
    {
      *whyNot = why;
    }
    return std::nullopt;
  };
  const std::string file = folder + "/case.json";
  // Ours are a few kB: anything else (a planted 1 GB file, a FIFO) is not read, and the case is
  // computed again.
  std::error_code error;
  if (!std::filesystem::exists(file, error))
  {
    return skip(std::string()); // never run: nothing to say
  }
  if (!std::filesystem::is_regular_file(file, error) || std::filesystem::file_size(file, error) > MaxCaseRecordBytes || error)
  {
    return skip("its case.json is not one a run wrote");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in)
  {
    return skip("its case.json cannot be read");
  }
  try
  {
    const nlohmann::json record = nlohmann::json::parse(in);
    // The same inputs as now (paths, sizes, times and contents, compared as JSON text), and every
    // file the run wrote as it wrote it.
    if (record.at("case") != c.Name || nlohmann::json(CohortCaseInputsJson(c)).dump() != record.at("inputs").dump())
    {
      return skip("an input changed since its run (a file's size, time or content, or a file added or gone)");
    }
    const std::string changed = record.contains("outputs") ? OutputsChanged(record.at("outputs"), folder) : "case.json lists no outputs";
    if (!changed.empty())
    {
      return skip(changed);
    }
    CohortCaseResult result;
    result.Case = c.Name;
    result.Resumed = true;
    for (const auto& row : record.at("classes"))
    {
      result.Classes.push_back({ row.at("class").get<std::string>(), OptionalOf(row.at("tip_min_mm")),
        OptionalOf(row.at("surface_min_mm")), OptionalOf(row.at("penetration_max_mm3")), row.at("breach_frames").get<int>(),
        OptionalOf(row.at("penetration_depth_max_mm")) });
    }
    result.MarginMinMm = OptionalOf(record.at("margin_min_mm"));
    for (const auto& t : record.at("tumours"))
    {
      result.Tumours.push_back({ t.at("id").get<std::string>(), OptionalOf(t.at("margin_min_mm")), OptionalOf(t.at("surface_min_mm")) });
    }
    result.Frames = record.at("frames").get<int>();
    result.Tips = record.at("tips").get<int>();
    return result;
  }
  catch (const std::exception&)
  {
    return skip("its case.json is damaged"); // not one of ours: the case is run again
  }
}
} // namespace vp
