// vesselproximity bench: the distance engines side by side with the brute-force reference, on
// vessel meshes grown to fixed triangle counts, in one run.
#include "vpArguments.h"
#include "vpOutputFile.h"
#include "vpEngineBenchmark.h"
#include "vpAnalyticShapes.h"
#include "vpScalpelLoader.h"
#include "vpPointCsv.h"
#include "vpPoseFile.h"
#include "vpTrackingOptions.h"
#include "vtkScalpelModel.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace vp
{
namespace
{
using Json = BenchJson;

std::vector<std::size_t> ParseSizes(const std::string& text)
{
  std::vector<std::size_t> sizes;
  std::size_t start = 0;
  while (start < text.size())
  {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const long long v = std::strtoll(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v < 1 || v > 100000000LL)
    {
      throw InputError("--sizes", "expected positive triangle counts separated by commas, got '" + item + "'");
    }
    sizes.push_back(static_cast<std::size_t>(v));
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  return sizes;
}

/// --engines: a list of exact, zbuffer, replay, live, penetration, breach and models.
std::set<std::string> ParseBenchEngines(const cli::ParsedArguments& args)
{
  static const std::set<std::string> known = { "exact", "zbuffer", "replay", "live", "penetration", "breach", "models" };
  const std::string expected = "expected a list of exact, zbuffer, replay, live, penetration, breach and models";
  std::set<std::string> engineNames;
  std::istringstream engineList(args.GetString("engines"));
  for (std::string name; std::getline(engineList, name, ',');)
  {
    if (!known.count(name))
    {
      throw InputError("--engines", expected + ", got '" + name + "'");
    }
    engineNames.insert(name);
  }
  if (engineNames.empty())
  {
    throw InputError("--engines", expected);
  }
  return engineNames;
}

/// The live part: per phase, latency beside the frame's own compute, drops and memory.
void PrintLiveTable(const Json& live)
{
  std::printf("\nlive over OpenIGTLink (loopback), %s, %d classes:\n", live["engine"].get<std::string>().c_str(), live["classes"].get<int>());
  std::printf("  %-10s %8s %8s %8s %9s  %-26s %-26s %s\n", "phase", "rate Hz", "frames", "dropped", "rejected",
    "latency ms median/p95/max", "frame ms median/p95/max", "resident MB 5 s -> end");
  for (const char* phase : { "latency", "tip_only", "zbuffer", "sustained" })
  {
    if (live.contains(phase) && live[phase].contains("unavailable"))
    {
      std::printf("  %-10s unavailable: %s\n", phase, live[phase]["unavailable"].get<std::string>().c_str());
    }
    if (!live.contains(phase) || live[phase].contains("unavailable"))
    {
      continue;
    }
    const Json& p = live[phase];
    auto triple = [](const Json& q) {
      char text[64];
      std::snprintf(text, sizeof text, "%.3f / %.3f / %.3f", q["median"].get<double>(), q["p95"].get<double>(), q["max"].get<double>());
      return std::string(q.is_null() ? "-" : text);
    };
    char memory[64] = "-";
    if (!p["resident_mb_after_5s"].is_null())
    {
      std::snprintf(memory, sizeof memory, "%.1f -> %.1f (%+.1f%%)", p["resident_mb_after_5s"].get<double>(),
        p["resident_mb_end"].get<double>(), p["resident_growth_percent"].get<double>());
    }
    std::printf("  %-10s %8.0f %8zu %8zu %9zu  %-26s %-26s %s\n", phase, p["rate_hz"].get<double>(), p["frames"].get<std::size_t>(),
      p["poses_dropped"].get<std::size_t>(), p["rejected"].get<std::size_t>(), triple(p["latency_ms"]).c_str(),
      triple(p["frame_ms"]).c_str(), memory);
  }
}

/// The penetration sweep: per engine and depth band the frame's median and p95 and the volume's
/// largest error, then the totals against the closed forms and the bounds.
void PrintPenetrationTable(const Json& sweep)
{
  std::printf("\npenetration sweep (%d poses), full frame through the logic:\n", sweep["poses"].get<int>());
  std::printf("  %-9s %-10s %22s %16s %10s\n", "engine", "depth mm", "frame ms median/p95", "volume error", "relative");
  for (const char* engine : { "exact", "zbuffer" })
  {
    if (!sweep.contains(engine))
    {
      continue;
    }
    const Json& e = sweep[engine];
    if (e.contains("unavailable"))
    {
      std::printf("  %-9s %s\n", engine, e["unavailable"].get<std::string>().c_str());
      continue;
    }
    for (const Json& b : e["bands"])
    {
      std::printf("  %-9s %4.1f-%-5.1f %10.3f / %-9.3f %12.2f mm3 %9.1f%%\n", engine, b["depth_from_mm"].get<double>(),
        b["depth_to_mm"].get<double>(), b["median_ms"].get<double>(), b["p95_ms"].get<double>(),
        b["max_volume_error_mm3"].get<double>(), 100.0 * b["max_volume_error_relative"].get<double>());
    }
    std::printf("  %-9s all        %10.3f / %-9.3f  depth error <= %.3f mm, volume <= %.1f%% from 1 mm; %d outside their "
                "bound, %d below the truth beyond it, %d unknown\n",
      engine, e["frame_ms"]["median_ms"].get<double>(), e["frame_ms"]["p95_ms"].get<double>(), e["max_depth_error_mm"].get<double>(),
      100.0 * e["max_volume_error_relative_from_1mm"].get<double>(), e["answers_outside_their_bound"].get<int>(),
      e["answers_below_truth_beyond_bound"].get<int>(), e["answers_unknown"].get<int>());
  }
  const Json& f = sweep["fcl_primitives"];
  std::printf("  FCL's convex primitives (depth only): %.4f / %.4f ms, depth error <= %.4f mm\n", f["median_ms"].get<double>(),
    f["p95_ms"].get<double>(), f["max_depth_error_mm"].get<double>());
}

/// The replay's instrument: --scalpel (tip from --tip, its JSON or the finder), else a plain shaft.
vtkSmartPointer<vtkScalpelModel> ReplayScalpel(const cli::ParsedArguments& args)
{
  vtkSmartPointer<vtkScalpelModel> scalpel;
  if (args.IsSet("scalpel"))
  {
    scalpel = LoadScalpel(args.GetString("scalpel"), ParseTipDefinition(args));
  }
  else
  {
    scalpel = vtkSmartPointer<vtkScalpelModel>::New();
    const double z[3] = { 0, 0, 1 };
    const double centre[3] = { 0, 0, -60 };
    scalpel->SetModel(MakeCappedCylinder(centre, z, 1.5, 120.0, 24));
    scalpel->SetTipSource("built-in shaft: tip (0, 0, 0), axis +z");
  }
  return scalpel;
}

void PrintExactTable(const Json& sizes)
{
  std::printf("%-15s %9s | %9s %10s %10s %10s | %9s %10s | %10s | %9s %9s\n", "class", "triangles", "build ms",
    "exact med", "exact p95", "tracked", "vtk build", "vtk med", "brute med", "speedup", "diff mm");
  for (const Json& s : sizes)
  {
    for (const Json& c : s["classes"])
    {
      std::printf("%-15s %9zu | %9.1f %10.4f %10.4f %10.4f | %9.1f %10.4f | %10.3f | %8.0fx %9.1e\n",
        c["class"].get<std::string>().c_str(), c["triangles"].get<std::size_t>(), c["exact"]["build_ms"].get<double>(),
        c["exact"]["random"]["median_ms"].get<double>(), c["exact"]["random"]["p95_ms"].get<double>(),
        c["exact"]["tracked"]["median_ms"].get<double>(), c["vtk_static_cell_locator"]["build_ms"].get<double>(),
        c["vtk_static_cell_locator"]["random"]["median_ms"].get<double>(),
        c["brute"]["random"]["median_ms"].get<double>(), c["speedup_exact_vs_brute"].get<double>(),
        c["max_abs_diff_mm"]["exact_vs_brute"].get<double>());
      if (c["exact"].contains("random_without_inside_vote"))
      {
        std::printf("%-15s   not closed: inside by the vote of rays, median %.4f ms against %.4f without it (%.2fx)\n", "",
          c["exact"]["random"]["median_ms"].get<double>(), c["exact"]["random_without_inside_vote"]["median_ms"].get<double>(),
          c["exact"]["inside_vote_cost_ratio"].get<double>());
      }
    }
  }
}

void PrintZBufferTimes(const Json& z)
{
  std::printf("\nz-buffer on %s, cell %.3f mm, error bound %.3f mm, range %.0f mm (times per query, all classes)\n",
    z["device"].get<std::string>().c_str(), z["cell_mm"].get<double>(), z["error_bound_mm"].get<double>(),
    z["range_mm"].get<double>());
  std::printf("%10s %10s | %9s %9s | %10s %10s %10s | %10s %7s | %10s %10s | %9s %8s\n", "tris/class", "total",
    "build ms", "render ms", "cached med", "cached p95", "paper med", "moving med", "renders", "exact med", "brute med",
    "max diff", "outside");
  for (const Json& s : z["sizes"])
  {
    std::printf("%10zu %10zu | %9.1f %9.1f | %10.3f %10.3f %10.3f | %10.3f %7d | %10.4f %10.2f | %9.4f %8d\n",
      s["triangles_per_class"].get<std::size_t>(), s["triangles"].get<std::size_t>(), s["build_ms"].get<double>(),
      s["render"]["median_ms"].get<double>(), s["cached"]["median_ms"].get<double>(),
      s["cached"]["p95_ms"].get<double>(), s["paper_mode"]["median_ms"].get<double>(),
      s["moving_box"]["median_ms"].get<double>(), s["moving_box"]["renders"].get<int>(),
      s["exact_all_classes"]["median_ms"].get<double>(), s["brute_all_classes"]["median_ms"].get<double>(),
      s["max_abs_diff_vs_exact_mm"].get<double>(), s["outside_bound"].get<int>());
  }
  std::printf("cached query time, largest size / smallest: %.2f\n", z["cached_query_ratio_largest_to_smallest"].get<double>());
  for (const char* key : { "largest_beside_smallest", "fine_cell_beside_cell" })
  {
    if (z.contains(key))
    {
      const Json& c = z[key];
      std::printf("side by side (%s): %zu triangles at %.3f mm cells %.4f / %.4f ms (device %.4f), %zu at %.3f mm "
                  "%.4f / %.4f ms (device %.4f): ratio %.2f median, %.2f p95, %.2f on the device\n",
        key, c["first"]["triangles"].get<std::size_t>(), c["first"]["cell_mm"].get<double>(),
        c["first"]["cached"]["median_ms"].get<double>(), c["first"]["cached"]["p95_ms"].get<double>(),
        c["first"]["cached_device"]["median_ms"].get<double>(), c["second"]["triangles"].get<std::size_t>(),
        c["second"]["cell_mm"].get<double>(), c["second"]["cached"]["median_ms"].get<double>(),
        c["second"]["cached"]["p95_ms"].get<double>(), c["second"]["cached_device"]["median_ms"].get<double>(),
        c["ratio_median"].get<double>(), c["ratio_p95"].get<double>(), c["ratio_device_median"].get<double>());
      std::printf("  tiles per query (median, all classes): %.0f dispatched, %.0f listed at %.3f mm; %.0f, %.0f at %.3f mm\n",
        c["first"]["tiles_dispatched_median"].get<double>(), c["first"]["tiles_listed_median"].get<double>(),
        c["first"]["cell_mm"].get<double>(), c["second"]["tiles_dispatched_median"].get<double>(),
        c["second"]["tiles_listed_median"].get<double>(), c["second"]["cell_mm"].get<double>());
    }
  }
}

/// A batch under two settings taken in turn (bench's TwoSides), a row per size and side: the
/// batch's median and p95, tips per second, the device's time and one part of the call's.
void PrintTwoSides(const Json& z, const char* key, const char* title, const std::array<const char*, 2>& sides,
  const char* part, const char* partTitle)
{
  std::printf("%10s | %-18s %14s %14s %12s %12s %14s %12s\n", "tris/class", title, "batch med ms", "batch p95 ms",
    "tips/s", "device ms", partTitle, "differing");
  for (const Json& s : z["sizes"])
  {
    const Json& two = s[key];
    for (const char* side : sides)
    {
      const Json& w = two[side];
      std::printf("%10zu | %-18s %14.2f %14.2f %12.0f %12.2f %14.2f %12d\n", s["triangles_per_class"].get<std::size_t>(),
        side, w["median_ms"].get<double>(), w["p95_ms"].get<double>(), w["tips_per_second"].get<double>(),
        w["parts"]["device"]["median_ms"].get<double>(), w["parts"][part]["median_ms"].get<double>(),
        two["answers_differing"].get<int>());
    }
  }
}

/// The cached tip's query, with its axis, on the host and on the device.
void PrintZBufferQueryTimes(const Json& z)
{
  std::printf("%10s | %14s %14s | %14s %14s %14s %14s\n", "tris/class", "query med ms", "on device med",
    "axis med ms", "axis p95 ms", "on device med", "on device p95");
  for (const Json& s : z["sizes"])
  {
    std::printf("%10zu | %14.4f %14.4f | %14.4f %14.4f %14.4f %14.4f\n", s["triangles_per_class"].get<std::size_t>(),
      s["cached"]["median_ms"].get<double>(), s["cached_device"]["median_ms"].get<double>(),
      s["cached_with_axis"]["median_ms"].get<double>(), s["cached_with_axis"]["p95_ms"].get<double>(),
      s["cached_with_axis_device"]["median_ms"].get<double>(), s["cached_with_axis_device"]["p95_ms"].get<double>());
  }
}

/// Batches: time, tips per second beside the exact engine's, and where the time went.
void PrintZBufferBatches(const Json& z)
{
  std::printf("%10s | %14s %14s %16s | %14s\n", "tris/class", "batch med ms", "batch p95 ms", "z-buffer tips/s",
    "exact tips/s");
  for (const Json& s : z["sizes"])
  {
    std::printf("%10zu | %14.2f %14.2f %16.0f | %14.0f   (%zu tips, %zu a submission, %d answers differ from single queries)\n",
      s["triangles_per_class"].get<std::size_t>(), s["batched"]["median_ms"].get<double>(),
      s["batched"]["p95_ms"].get<double>(), s["batched"]["tips_per_second"].get<double>(),
      s["exact_batched"]["tips_per_second"].get<double>(), s["batched"]["tips"].get<std::size_t>(),
      s["batch_capacity"].get<std::size_t>(), s["batched"]["answers_differing_from_single_queries"].get<int>());
    const Json& b = s["batched"];
    const Json& p = b["parts"];
    std::printf("%10s | of which: device %.2f ms (%.0f tips/s on the device; listing %.2f, visiting %.2f, reducing %.2f), "
                "host wait %.2f ms, %zu inside votes %.2f ms, ceilings %.2f ms, answers read %.2f ms, tips ordered %.2f ms, "
                "%zu submissions\n",
      "", p["device"]["median_ms"].get<double>(), b["device_tips_per_second"].get<double>(),
      p["device_listing"]["median_ms"].get<double>(), p["device_visiting"]["median_ms"].get<double>(),
      p["device_reducing"]["median_ms"].get<double>(),
      p["submit_wait"]["median_ms"].get<double>(), p["votes_in_last_call"].get<std::size_t>(),
      p["votes"]["median_ms"].get<double>(), p["ceilings"]["median_ms"].get<double>(), p["read"]["median_ms"].get<double>(),
      p["order"]["median_ms"].get<double>(), p["submissions_in_last_call"].get<std::size_t>());
  }
}

/// The answer ceilings off and on, for random and tracked tips.
void PrintZBufferCeilings(const Json& z)
{
  std::printf("%10s | %-8s %22s %22s %22s %12s\n", "tris/class", "ceilings", "off med / p95 ms", "on med / p95 ms",
    "device off / on med", "tiles (med)");
  for (const Json& s : z["sizes"])
  {
    const Json& c = s["ceilings"];
    for (const char* walk : { "random", "tracked" })
    {
      const Json& w = c[walk];
      std::printf("%10zu | %-8s %10.4f / %9.4f %10.4f / %9.4f %10.4f / %9.4f %11.0f%%\n",
        s["triangles_per_class"].get<std::size_t>(), walk, w["off"]["median_ms"].get<double>(), w["off"]["p95_ms"].get<double>(),
        w["on"]["median_ms"].get<double>(), w["on"]["p95_ms"].get<double>(), w["off_device"]["median_ms"].get<double>(),
        w["on_device"]["median_ms"].get<double>(), 100.0 * w["tiles_share_median"].get<double>());
    }
    std::printf("%10zu | batched: %.0f tips/s off, %.0f on; blocks built in %.1f ms; %d answers differ\n",
      s["triangles_per_class"].get<std::size_t>(), c["batched_off"]["tips_per_second"].get<double>(),
      c["batched_on"]["tips_per_second"].get<double>(), c["build_ms"].get<double>(), c["answers_differing"].get<int>());
  }
}

/// Tiles listed by the host off and on, and single tips listed by the device.
void PrintZBufferTileListing(const Json& z)
{
  std::printf("%10s | %-12s %16s %16s %22s %22s %10s\n", "tris/class", "tile listing", "batch tips/s", "tiles per tip",
    "single med / p95 ms", "device med / p95 ms", "differing");
  for (const Json& s : z["sizes"])
  {
    const Json& t = s["tile_listing"];
    for (const char* side : { "off", "on" })
    {
      const Json& w = t[side];
      const bool on = side[1] == 'n';
      std::printf("%10zu | %-12s %16.0f %16.1f %10.4f / %9.4f %10.4f / %9.4f %10d\n",
        s["triangles_per_class"].get<std::size_t>(), side, w["batched_tips_per_second"].get<double>(),
        on ? t["tiles_listed_per_tip"].get<double>() : t["tiles_dispatched_per_tip"].get<double>(),
        w["single"]["median_ms"].get<double>(), w["single"]["p95_ms"].get<double>(),
        w["single_device"]["median_ms"].get<double>(), w["single_device"]["p95_ms"].get<double>(),
        t["answers_differing"].get<int>());
    }
    // A few tips are listed by the host; the device's own listing of a single tip beside it.
    const Json& on = t["on"];
    std::printf("%10s | %-12s %16s %16s %10.4f / %9.4f %10.4f / %9.4f   (single tips listed by the device)\n", "",
      "on, device", "", "", on["single_device_listed"]["median_ms"].get<double>(),
      on["single_device_listed"]["p95_ms"].get<double>(), on["single_device_listed_device"]["median_ms"].get<double>(),
      on["single_device_listed_device"]["p95_ms"].get<double>());
  }
}

/// A single tip's time by part, random and tracked.
void PrintZBufferSingleTipParts(const Json& z)
{
  std::printf("%10s | single tip, median / p95 ms: %-s\n", "tris/class",
    "call, device, host wait, votes, ceilings, host listing, answers read");
  for (const Json& s : z["sizes"])
  {
    for (const char* walk : { "random", "tracked" })
    {
      const Json& t = s[walk[0] == 'r' ? "single_tip_times" : "single_tip_times_tracked"];
      std::printf("%10zu | %-7s", s["triangles_per_class"].get<std::size_t>(), walk);
      const char* separator = "";
      for (const char* part : { "total", "device", "submit_wait", "votes", "ceilings", "host_listing", "read" })
      {
        std::printf("%s %.4f / %.4f", separator, t[part]["median_ms"].get<double>(), t[part]["p95_ms"].get<double>());
        separator = ",";
      }
      std::printf("\n");
    }
  }
}

/// The batch's passes: per tile or per pixel, one invocation per tip or not.
void PrintZBufferBatchPasses(const Json& z)
{
  std::printf("%10s | %-31s %10s %10s %10s %14s %12s %12s %10s %10s\n", "tris/class", "batch pass", "med ms", "p95 ms",
    "tips/s", "device tips/s", "listing ms", "visiting ms", "tiles/tip", "differing");
  for (const Json& s : z["sizes"])
  {
    const Json& b = s["batch_passes"];
    for (const char* pass :
      { "per_tile_listed", "per_pixel_listed", "per_tile_listed_per_invocation", "per_pixel_listed_per_invocation" })
    {
      const Json& w = b[pass];
      std::printf("%10zu | %-31s %10.2f %10.2f %10.0f %14.0f %12.2f %12.2f %10.1f %10d\n",
        s["triangles_per_class"].get<std::size_t>(), pass, w["batched"]["median_ms"].get<double>(),
        w["batched"]["p95_ms"].get<double>(), w["tips_per_second"].get<double>(), w["device_tips_per_second"].get<double>(),
        w["device_listing"]["median_ms"].get<double>(), w["device_visiting"]["median_ms"].get<double>(),
        w["tiles_listed_per_tip"].get<double>(), w["answers_differing_from_per_tile"].get<int>());
    }
  }
}

/// The inside votes of a batch on open surfaces: from the vote field and from the rays.
void PrintZBufferBatchVotes(const Json& z)
{
  for (const Json& s : z["sizes"])
  {
    if (s.contains("batch_votes"))
    {
      const Json& v = s["batch_votes"];
      std::printf("%10zu | batch votes, median / p95 ms: field %.2f / %.2f (batch %.2f / %.2f), rays %.2f / %.2f (batch "
                  "%.2f / %.2f); votes differing %d, distances %d\n",
        s["triangles_per_class"].get<std::size_t>(), v["field"]["parts"]["votes"]["median_ms"].get<double>(),
        v["field"]["parts"]["votes"]["p95_ms"].get<double>(), v["field"]["median_ms"].get<double>(),
        v["field"]["p95_ms"].get<double>(), v["rays"]["parts"]["votes"]["median_ms"].get<double>(),
        v["rays"]["parts"]["votes"]["p95_ms"].get<double>(), v["rays"]["median_ms"].get<double>(),
        v["rays"]["p95_ms"].get<double>(), v["votes_differing"].get<int>(), v["distances_differing"].get<int>());
    }
  }
}

/// The z-buffer's query tables, one after another.
void PrintZBufferQueries(const Json& z)
{
  PrintZBufferQueryTimes(z);
  PrintZBufferBatches(z);
  PrintZBufferCeilings(z);
  PrintZBufferTileListing(z);
  PrintZBufferSingleTipParts(z);
  PrintZBufferBatchPasses(z);
  // The batch with one submission in flight and with two (the host's work beside the device's),
  // and with its tips as given and in space order (neighbours side by side).
  PrintTwoSides(z, "batch_in_flight", "in flight", { "one", "two" }, "submit_wait", "host wait ms");
  PrintTwoSides(z, "batch_order", "batch order", { "as_given", "spatial" }, "order", "ordering ms");
  PrintZBufferBatchVotes(z);
}

void PrintReplayTable(const Json& r)
{
  std::printf("\nreplay: %zu poses, %zu classes, %zu triangles, scalpel of %lld triangles\n",
    r["poses"].get<std::size_t>(), r["classes"].get<std::size_t>(), r["triangles"].get<std::size_t>(),
    r["tool_triangles"].get<long long>());
  std::printf("  %-36s %8s %14s %12s %12s\n", "engine", "frames", "frames/s", "median ms", "p95 ms");
  for (const char* key :
    { "exact_tip", "exact_tip_and_surface", "fcl_surface", "spheres_tip_and_surface", "exact_tip_and_surface_within_caution",
      "zbuffer_cached", "zbuffer_tip_and_surface", "zbuffer_full_frame", "brute_tip" })
  {
    if (r.contains(key))
    {
      std::printf("  %-36s %8zu %14.0f %12.4f %12.4f\n", key, r[key]["frames"].get<std::size_t>(),
        r[key]["frames_per_second"].get<double>(), r[key]["frame_median_ms"].get<double>(), r[key]["frame_p95_ms"].get<double>());
    }
  }
  for (const char* key : { "fcl_surface", "spheres_tip_and_surface" })
  {
    std::printf("  %s against exact_tip_and_surface: largest difference %.2e mm, %d in/out of range disagreements\n", key,
      r[key]["vs_exact_tip_and_surface"]["max_abs_diff_mm"].get<double>(),
      r[key]["vs_exact_tip_and_surface"]["in_range_disagreements"].get<int>());
  }
  if (r.contains("zbuffer_cached"))
  {
    std::printf("  z-buffer on %s: layers %.0f ms once; largest |zbuffer - exact| %.4f mm, bound %.3f mm, %d outside\n",
      r["zbuffer_cached"]["device"].get<std::string>().c_str(), r["zbuffer_cached"]["build_and_render_ms"].get<double>(),
      r["zbuffer_cached"]["max_abs_diff_vs_exact_mm"].get<double>(), r["zbuffer_cached"]["error_bound_mm"].get<double>(),
      r["zbuffer_cached"]["outside_bound"].get<int>());
  }
  if (r.contains("zbuffer_tip_and_surface"))
  {
    const Json& w = r["zbuffer_tip_and_surface"];
    const Json& v = w["vs_exact_tip_and_surface"];
    std::printf("  z-buffer whole instrument: field and samples %.0f ms once (%.0f MB); against exact: bound %.3f mm "
                "(%.3f where exact < 5 mm), %d outside it, %d farther than exact\n",
      w["build_ms"].get<double>(), w["field_memory_mb"].get<double>(), v["max_error_bound_mm"].get<double>(),
      v["max_error_bound_within_5mm"].get<double>(), v["outside_bound"].get<int>(), v["farther_than_reference"].get<int>());
  }
  if (r.contains("zbuffer_full_frame"))
  {
    const Json& v = r["zbuffer_full_frame"]["vs_exact_penetration"];
    std::printf("  z-buffer penetration against exact: %d overlapping answers, largest depth difference %.3f mm, volume %.1f "
                "mm3, %d outside the bounds\n",
      v["answers_with_exact_overlap"].get<int>(), v["max_depth_diff_mm"].get<double>(), v["max_volume_diff_mm3"].get<double>(),
      v["outside_bounds"].get<int>());
  }
}

/// The breach: per engine the frame's median and p95 over the run, its penetrating frames and
/// each overlap band, the volume and depth against the fine reference, FCL beside.
void PrintBreachTable(const Json& breach)
{
  const long long budget = breach["query_budget"].get<long long>();
  const std::string budgetText = budget > 0 ? std::to_string(budget) + " queries a class" : "no query budget";
  std::printf("\nbreach (%zu poses, %d penetrating, overlap up to %.0f mm3; %s; %s), full frame through the logic, "
              "median / p95 ms:\n",
    breach["poses"].get<std::size_t>(), breach["penetrating_poses"].get<int>(), breach["largest_overlap_mm3"].get<double>(),
    breach["scalpel"].get<std::string>().c_str(), budgetText.c_str());
  auto cell = [](const Json& t) {
    char text[48];
    std::snprintf(text, sizeof text, "%.2f / %.2f", t["median_ms"].get<double>(), t["p95_ms"].get<double>());
    return std::string(t["queries"].get<std::size_t>() == 0 ? "-" : text);
  };
  std::printf("  %-9s %-15s %-15s %-15s %-15s %-15s %s\n", "engine", "run", "penetrating", "< 100 mm3", "100-1000",
    "> 1000", "volume error / depth error (max)");
  for (const char* engine : { "exact", "zbuffer", "exact_without_budget" })
  {
    if (!breach.contains(engine))
    {
      continue;
    }
    const Json& e = breach[engine];
    if (e.contains("unavailable"))
    {
      std::printf("  %-9s %s\n", engine, e["unavailable"].get<std::string>().c_str());
      continue;
    }
    std::printf("  %-9s %-15s %-15s %-15s %-15s %-15s %.1f mm3 (%.1f%% from 1 mm) / %.2f mm; %d outside the contract, "
                "%d below the truth beyond the bounds\n",
      std::string(engine) == "exact_without_budget" ? "no budget" : engine, cell(e["frame_ms"]).c_str(), cell(e["penetrating_frame_ms"]).c_str(), cell(e["bands"][0]).c_str(),
      cell(e["bands"][1]).c_str(), cell(e["bands"][2]).c_str(), e["max_volume_error_mm3"].get<double>(),
      100.0 * e["max_volume_error_relative_from_1mm"].get<double>(), e["max_depth_error_mm"].get<double>(),
      e["answers_outside_contract"].get<int>(), e["answers_below_truth_beyond_bounds"].get<int>());
  }
  std::printf("  %-9s %-15s (the whole instrument's distance only)\n", "FCL", cell(breach["fcl_surface"]).c_str());
  if (breach.contains("zbuffer") && breach["zbuffer"].contains("device"))
  {
    std::printf("  z-buffer on %s\n", breach["zbuffer"]["device"].get<std::string>().c_str());
  }
}

/// The models: read, each class's build and the total, as given and stacked.
void PrintModelsTable(const Json& models)
{
  std::printf("\nmodels (BuildVesselModels, %d runs each; the stacked series %d times as long; voxels %s):\n",
    models["runs"].get<int>(), models["copies"].get<int>(), models["voxels_match"].get<bool>() ? "match" : "DO NOT MATCH");
  auto cell = [](const Json& t) {
    char text[48];
    std::snprintf(text, sizeof text, "%.0f / %.0f", t["median_ms"].get<double>(), t["p95_ms"].get<double>());
    return std::string(text);
  };
  for (const char* which : { "as_given", "stacked" })
  {
    const Json& m = models[which];
    std::printf("  %-8s %4d slices  read %-11s built %-11s written %-9s built and written %-11s ms (median / p95)\n",
      which, m["slices"].get<int>(), cell(m["read"]).c_str(), cell(m["total"]).c_str(), cell(m["write"]).c_str(),
      cell(m["built_and_written"]).c_str());
    for (const Json& c : m["classes"])
    {
      std::printf("    %-16s %10lld voxels %9lld triangles  build %s ms\n", c["class"].get<std::string>().c_str(),
        c["voxels"].get<long long>(), c["triangles"].get<long long>(), cell(c["build"]).c_str());
    }
  }
}

void PrintBenchReport(Json& report)
{
  if (report.contains("sizes"))
  {
    PrintExactTable(report["sizes"]);
  }
  if (report.contains("zbuffer"))
  {
    PrintZBufferTimes(report["zbuffer"]);
    PrintZBufferQueries(report["zbuffer"]);
  }
  if (report.contains("replay"))
  {
    PrintReplayTable(report["replay"]);
  }
  if (report.contains("live"))
  {
    PrintLiveTable(report["live"]);
  }
  if (report.contains("penetration"))
  {
    PrintPenetrationTable(report["penetration"]);
  }
  if (report.contains("breach"))
  {
    PrintBreachTable(report["breach"]);
  }
  if (report.contains("models"))
  {
    PrintModelsTable(report["models"]);
  }
}

/// What each part of the bench measures: the command's long help.
std::string BenchHelp()
{
  return "Grows each vessel mesh to each size (longest-edge bisection: same surface, more triangles) and measures in one run:\n"
    "exact: per class, the exact engine (Embree BVH) on random tips and on a tracked tip (0.5 mm steps, the previous "
    "answer bounding the search), VTK's vtkStaticCellLocator, and the paper's brute-force CPU algorithm; the speed-up "
    "and the largest disagreement.\n"
    "zbuffer: all classes at once, the Vulkan z-buffer engine: rendering the layers, per-query time with cached layers "
    "(exact-interval and paper's mode), the moving box on the tracked tip, beside the exact engine and brute force on "
    "the same tips; the largest |zbuffer - exact| against the error bound. Side by side, query by query (so that both "
    "see the device in the same state: a GPU's clock follows its load), the smallest and the largest size, and with "
    "--fine-cell the smallest size at that cell beside the set one.\n"
    "replay: the tracking pipeline (vtkScalpelTrackingLogic) on the vessels as given, all classes, a scalpel following "
    "the tracked tip: frames per second, exact (tip; tip and whole surface), FCL's whole surface on the same poses (its "
    "answers compared with ours), z-buffer on cached layers: tip, tip and whole instrument from its distance field, "
    "and the full frame with its penetration (with zbuffer among the engines), brute force on the first brute-queries "
    "frames.\n"
    "live: the same logic (exact, tip and whole instrument) on a live OpenIGTLink stream over loopback: a tracker "
    "thread streams the replay's poses at --live-rate-hz for --live-seconds, then at --sustained-rate-hz for "
    "--sustained-seconds, and reads the results back; per frame the latency from a pose's arrival to its results "
    "sent, beside the frame's own compute time, the poses dropped, and the resident memory after 5 s and at the end; "
    "with breach among the engines the breach's poses instead, and beside them the same stream with the tip alone and "
    "through the z-buffer engine. "
    "penetration: a closed cylinder tool (radius 1.5 mm) pushed 0.2 to 10 mm into a sphere vessel (radius 10 mm) "
    "of three classes, --penetration-poses steps: the full frame (tip, whole instrument, penetration) through the logic, "
    "exact and (with a Vulkan device) z-buffer, median and p95 per depth band, the penetration depth and volume against "
    "their closed forms and stated bounds, beside FCL's penetration depth of the convex primitives.\n"
    "breach: the instrument (--scalpel, default the built-in CUSA handpiece) pushed into each class of the vessels "
    "(--vessels, say a models folder's STLs) along the inward normal at --breach-points surface points per class, "
    "2 mm outside, up to --breach-push-mm in and withdrawn half way: the full frame through the logic, exact and "
    "(with a Vulkan device) z-buffer, median and p95 over the run, its penetrating frames and each overlap band "
    "(< 100, 100-1,000, > 1,000 mm3), volume and depth against a fine reference (the exact walk at 0.2 mm without a "
    "budget), the exact engine without a budget and FCL's whole-instrument distance on the same poses beside.\n"
    "models: BuildVesselModels (read, each class's surface) on --models-input (a folder of DICOM label series, "
    "IRCADb's MASKS_DICOM) as given and with each series laid end to end --models-copies times (a longer scan of "
    "the same patient), --models-runs each; the stacked classes must hold the copies' voxels.\n"
    "Progress goes to stderr.";
}

/// The replay's instrument and poses, and how they are read.
std::vector<cli::Parameter> ReplayOptions()
{
  using cli::ParameterType;
  std::vector<cli::Parameter> replay = {
    Option(ParameterType::File, "scalpel", "The replay's instrument (default: a 120 mm shaft of 1.5 mm radius).").SetChannel(cli::Channel::Input),
    Option(ParameterType::File, "poses", "A pose file to replay (the demo's poses.csv, say) instead of the generated path.")
      .SetChannel(cli::Channel::Input),
  };
  for (const cli::Parameter& p : ScalpelTipOptions())
  {
    replay.push_back(p);
  }
  for (const cli::Parameter& p : PoseReadingOptions())
  {
    replay.push_back(p);
  }
  return replay;
}

} // namespace

cli::ModuleDescription DescribeBenchCommand()
{
  using cli::ParameterType;
  auto count = [](const char* flag, const char* def, const char* description) {
    return Option(ParameterType::Integer, flag, description).SetPlaceholder("N").SetDefault(def).SetRange(1, 100000000, 1);
  };
  cli::ParameterGroup engine = EngineOptions({});
  engine.Parameters.push_back(Option(ParameterType::Double, "fine-cell", "z-buffer: also the smallest size at this cell, beside the set one.").SetPlaceholder("MM"));
  return cli::ModuleDescription::Subcommand("vesselproximity bench", "engines side by side with the brute-force reference, JSON with --json",
    BenchHelp(),
    {
      { "Workload", "",
        { VesselsOption().SetDescription("The vessels (default: the built-in analytic vessels)."),
          Option(ParameterType::String, "sizes", "Triangles per class to grow each mesh to.").SetPlaceholder("N,N,...").SetDefault("50000,400000,1500000"),
          count("queries", "2000", "Random tips (and tracked steps, and replayed frames)."),
          count("brute-queries", "30", "Of those, how many the brute-force reference answers."),
          count("seed", "1", "The random seed."),
          Option(ParameterType::String, "engines", "Which parts to run: a list of exact, zbuffer, replay, live, penetration, breach and models.")
            .SetPlaceholder("exact,zbuffer,replay,live,penetration,breach,models")
            .SetDefault("exact,zbuffer") } },
      { "Replay", "", ReplayOptions() },
      { "Live", "",
        { Option(ParameterType::Double, "live-rate-hz", "The tracker's rate for the latency.").SetPlaceholder("HZ").SetDefault("60").SetRange(1, 10000, 1),
          Option(ParameterType::Double, "live-seconds", "How long at that rate.").SetPlaceholder("S").SetDefault("10").SetRange(1, 3600, 1),
          Option(ParameterType::Double, "sustained-rate-hz", "The rate held for the memory.").SetPlaceholder("HZ").SetDefault("1000").SetRange(1, 10000, 1),
          Option(ParameterType::Double, "sustained-seconds", "How long at that rate (0: not run).")
            .SetPlaceholder("S")
            .SetDefault("60")
            .SetRange(0, 3600, 1) } },
      { "Penetration", "",
        { count("penetration-poses", "100", "Depths of the penetration sweep, 0.2 to 10 mm.") } },
      { "Breach", "",
        { count("breach-points", "40", "Surface points per class the instrument is pushed in at (three poses each)."),
          Option(ParameterType::Double, "breach-push-mm", "The deepest push; the points' pushes rise evenly to it.")
            .SetPlaceholder("MM")
            .SetDefault("10")
            .SetRange(0.1, 100, 1),
          Option(ParameterType::Integer, "penetration-budget",
            "The penetration walk's most vessel-wall queries per class and frame (0: no limit).")
            .SetPlaceholder("N")
            .SetDefault(std::to_string(vtkScalpelPenetration::DefaultQueryBudget))
            .SetRange(0, 100000000, 1) } },
      { "Models", "",
        { Option(ParameterType::Directory, "models-input", "The label series the models part builds from (IRCADb's MASKS_DICOM).")
            .SetChannel(cli::Channel::Input),
          count("models-copies", "2", "How many times each series is laid end to end for the longer scan."),
          count("models-runs", "5", "Builds of each, for the median and p95.") } },
      engine,
      { "Output", "",
        { Switch("json", "Print the report as JSON instead of a table."),
          Option(ParameterType::File, "output", "Also write the JSON report to this file.").SetFlag("o").SetChannel(cli::Channel::Output).SetPlaceholder("FILE.json") } },
    });
}

namespace
{
/// The breach's and the models' parts of the request.
void ParseBreachAndModels(const cli::ParsedArguments& args, BenchmarkRequest& request)
{
  request.Breach.PointsPerClass = args.GetInteger("breachPoints");
  request.Breach.MaxPushMm = args.GetNumber("breachPushMm");
  request.Breach.Seed = static_cast<unsigned>(args.GetInteger("seed"));
  request.Breach.QueryBudget = args.GetInteger("penetrationBudget");
  if (request.Parts.count("breach") && args.IsSet("scalpel"))
  {
    request.BreachScalpel = ReplayScalpel(args);
  }
  if (request.Parts.count("models"))
  {
    if (!args.IsSet("modelsInput"))
    {
      throw InputError("--models-input", "the models part needs a folder of DICOM label series");
    }
    request.Models.Input = args.GetString("modelsInput");
    request.Models.Copies = args.GetInteger("modelsCopies");
    request.Models.Runs = args.GetInteger("modelsRuns");
  }
}

} // namespace

int RunBenchCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  // Everything is read and checked before any work: a bad value must not surface after minutes.
  BenchmarkRequest request;
  if (args.IsSet("fineCell") && !(args.GetNumber("fineCell") > 0.0))
  {
    throw InputError("--fine-cell", "must be a positive number of millimetres");
  }
  request.FineCellMm = args.IsSet("fineCell") ? std::optional<double>(args.GetNumber("fineCell")) : std::nullopt;
  request.Parts = ParseBenchEngines(args);
  request.SizesTriangles = ParseSizes(args.GetString("sizes"));
  request.ZBufferSettings = ParseEngineSettings("zbuffer", args);
  if (request.Parts.count("zbuffer")) // the device opened now: a missing one fails at once
  {
    request.ZBuffer = MakeBenchZBuffer(request.ZBufferSettings);
  }
  request.Live.RateHz = args.GetNumber("liveRateHz");
  request.Live.Seconds = args.GetNumber("liveSeconds");
  request.Live.SustainedRateHz = args.GetNumber("sustainedRateHz");
  request.Live.SustainedSeconds = args.GetNumber("sustainedSeconds");
  if (request.Parts.count("replay") || request.Parts.count("live"))
  {
    request.Scalpel = ReplayScalpel(args);
    request.Poses = args.IsSet("poses") ? ReadPoseFile(args.GetString("poses"), ParsePoseReading(args)) : std::vector<TrackedPose>();
  }
  request.Queries = args.GetInteger("queries");
  request.PenetrationPoses = args.GetInteger("penetrationPoses");
  ParseBreachAndModels(args, request);
  request.BruteQueries = std::min(request.Queries, args.GetInteger("bruteQueries"));
  request.Seed = static_cast<unsigned>(args.GetInteger("seed"));
  request.Vessels = args.IsSet("vessels") ? LoadVesselMeshes(ParsePairs(args.GetString("vessels"), "--vessels")) : BuiltInVessels();
  request.Source = args.IsSet("vessels") ? "files" : "built-in analytic vessels";
  Json report = RunBenchmark(request);
  if (args.IsSet("output"))
  {
    WriteFileAtomically(args.GetString("output"), report.dump(2) + "\n");
  }
  if (args.GetBoolean("json"))
  {
    std::cout << report.dump(2) << "\n";
    return 0;
  }
  PrintBenchReport(report);
  return 0;
}
} // namespace vp
