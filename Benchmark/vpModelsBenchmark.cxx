#include "vpModelsBenchmark.h"

#include "vpDcmtkFile.h"
#include "vpDicomLabelSeriesReader.h"
#include "vpClock.h"
#include "vpInputError.h"
#include "vpRunFolder.h"
#include "vpVesselLabelTable.h"
#include "vpVesselModelSet.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

namespace fs = std::filesystem;

namespace vp
{
using Json = BenchJson;

namespace
{
std::vector<fs::path> DicomFiles(const fs::path& folder)
{
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    if (entry.is_regular_file() && DicomLabelSeriesReader::IsDicomFile(entry.path().string()))
    {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::array<double, 3> ReadTriple(DcmItem& data, const DcmTagKey& tag, int first, const std::string& where)
{
  std::array<double, 3> v{};
  for (int k = 0; k < 3; ++k)
  {
    if (data.findAndGetFloat64(tag, v[k], first + k).bad())
    {
      throw InputError(where, "no slice position or orientation to stack it by");
    }
  }
  return v;
}

/// One series laid end to end copies times: each copy moved along the normal by the series'
/// length (its slice count times its spacing), so the slices stay evenly spaced.
int StackSeries(const fs::path& from, const fs::path& to, int copies)
{
  const std::vector<fs::path> files = DicomFiles(from);
  if (files.size() < 2)
  {
    throw InputError(from.string(), "fewer than two slices: nothing to stack");
  }
  std::vector<std::unique_ptr<DcmFileFormat>> slices;
  std::vector<std::array<double, 3>> positions;
  for (const fs::path& file : files)
  {
    slices.push_back(std::make_unique<DcmFileFormat>());
    LoadDicomFile(*slices.back(), file.string(), from.string());
    positions.push_back(ReadTriple(*slices.back()->getDataset(), DCM_ImagePositionPatient, 0, file.string()));
  }
  DcmDataset& first = *slices.front()->getDataset();
  const std::array<double, 3> row = ReadTriple(first, DCM_ImageOrientationPatient, 0, files.front().string());
  const std::array<double, 3> column = ReadTriple(first, DCM_ImageOrientationPatient, 3, files.front().string());
  const std::array<double, 3> normal = { row[1] * column[2] - row[2] * column[1], row[2] * column[0] - row[0] * column[2],
    row[0] * column[1] - row[1] * column[0] };
  double lo = 1e300, hi = -1e300;
  for (const auto& p : positions)
  {
    const double along = p[0] * normal[0] + p[1] * normal[1] + p[2] * normal[2];
    lo = std::min(lo, along), hi = std::max(hi, along);
  }
  const double n = static_cast<double>(files.size());
  const double length = (hi - lo) * n / (n - 1.0);
  fs::create_directories(to);
  for (int c = 0; c < copies; ++c)
  {
    for (std::size_t f = 0; f < files.size(); ++f)
    {
      DcmDataset& data = *slices[f]->getDataset();
      std::ostringstream position;
      position.precision(12);
      for (int k = 0; k < 3; ++k)
      {
        position << (k ? "\\" : "") << positions[f][k] + normal[k] * length * c;
      }
      char uid[100];
      data.putAndInsertString(DCM_ImagePositionPatient, position.str().c_str());
      data.putAndInsertString(DCM_SOPInstanceUID, dcmGenerateUniqueIdentifier(uid, SITE_INSTANCE_UID_ROOT));
      data.putAndInsertString(DCM_InstanceNumber, std::to_string(c * files.size() + f + 1).c_str());
      const fs::path out = to / (files[f].filename().string() + "_" + std::to_string(c));
      if (slices[f]->saveFile(out.string().c_str()).bad())
      {
        throw InputError(out.string(), "cannot write the stacked slice");
      }
    }
  }
  return static_cast<int>(files.size()) * copies;
}

/// Each part's times over the runs, and the classes as the last run built them; written as the
/// `models` command writes them (STLs and models.json through a run folder) into output.
Json TimeModelBuilds(const std::string& input, const std::string& output, int runs)
{
  std::vector<double> read, total, write, command;
  std::map<std::string, std::vector<double>> builds;
  Json classes = Json::array();
  int slices = 0;
  for (int run = 0; run < runs; ++run)
  {
    const VesselModelSet set = BuildVesselModels({ input }, VesselModelParameters(), [](const std::string&, double) {});
    const double t0 = NowMs();
    RunFolder folder(output, "models.json");
    WriteVesselModels(set, folder);
    write.push_back(NowMs() - t0);
    read.push_back(set.ReadMs);
    total.push_back(set.TotalMs);
    command.push_back(set.TotalMs + write.back());
    classes = Json::array();
    for (const VesselClassModel& m : set.Models)
    {
      builds[m.ClassName].push_back(m.BuildMs);
      int dims[3];
      m.Structures.front()->Grid.Labels->GetDimensions(dims);
      slices = dims[2];
      classes.push_back({ { "class", m.ClassName }, { "voxels", m.Voxels }, { "triangles", m.Surface->GetNumberOfPolys() },
        { "volume_mm3", m.VolumeMm3 } });
    }
  }
  for (Json& c : classes)
  {
    c["build"] = Timing(builds[c["class"].get<std::string>()]);
  }
  return { { "input", input }, { "slices", slices }, { "read", Timing(read) }, { "total", Timing(total) },
    { "write", Timing(write) }, { "built_and_written", Timing(command) }, { "classes", classes } };
}
} // namespace

int StackDicomSeries(const std::string& input, const std::string& output, int copies)
{
  if (copies < 1)
  {
    throw InputError("--models-copies", "must be 1 or more");
  }
  if (!DicomFiles(input).empty())
  {
    return StackSeries(input, fs::path(output) / fs::path(input).lexically_normal().filename(), copies);
  }
  const VesselLabelTable table = VesselLabelTable::Default();
  int slices = 0;
  for (const auto& entry : fs::directory_iterator(input))
  {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && !table.ClassOfName(name).empty() && !DicomFiles(entry.path()).empty())
    {
      slices = std::max(slices, StackSeries(entry.path(), fs::path(output) / name, copies));
    }
  }
  if (slices == 0)
  {
    throw InputError(input, "no label series the label table places: nothing to stack");
  }
  return slices;
}

Json BenchModels(const ModelsBenchSettings& settings)
{
  Json report;
  report["copies"] = settings.Copies;
  report["runs"] = settings.Runs;
  const fs::path work = fs::path(settings.WorkFolder);
  fs::remove_all(work);
  report["as_given"] = TimeModelBuilds(settings.Input, (work / "models").string(), settings.Runs);
  std::fprintf(stderr, "models: laying each series end to end %d times\n", settings.Copies);
  StackDicomSeries(settings.Input, (work / "stacked").string(), settings.Copies);
  report["stacked"] = TimeModelBuilds((work / "stacked").string(), (work / "models").string(), settings.Runs);
  fs::remove_all(work);
  bool match = true;
  const Json& given = report["as_given"]["classes"];
  const Json& stacked = report["stacked"]["classes"];
  for (std::size_t c = 0; c < given.size(); ++c)
  {
    match = match && c < stacked.size() &&
      stacked[c]["voxels"].get<long long>() == settings.Copies * given[c]["voxels"].get<long long>();
  }
  report["voxels_match"] = match && given.size() == stacked.size();
  return report;
}
} // namespace vp
