#include "vpFramesCsv.h"

#include "vpDangerLevels.h"
#include "vpInputError.h"

#include <set>

namespace vp
{
namespace
{
std::string Number(double value, const char* format = "%.4f")
{
  return FixedText(value, format);
}
} // namespace

namespace
{
std::string Header(const std::vector<std::string>& classes, bool surface, bool haptic, bool tumour);
} // namespace

void CheckFramesCsvColumns(const std::vector<std::string>& classes, bool tumour)
{
  const std::string header = Header(classes, true, true, tumour);
  std::set<std::string> seen;
  std::size_t begin = 0;
  while (begin < header.size())
  {
    std::size_t end = header.find_first_of(",\n", begin);
    const std::string column = header.substr(begin, end - begin);
    if (!seen.insert(column).second)
    {
      throw ParameterError("Vessels", "the class names give frames.csv two columns named '" + column +
          "': rename a class");
    }
    begin = end + 1;
  }
}

std::string FramesCsvHeader(const std::vector<std::string>& classes, bool surface, bool haptic, bool tumour)
{
  CheckFramesCsvColumns(classes, tumour);
  return Header(classes, surface, haptic, tumour);
}

namespace
{
std::string Header(const std::vector<std::string>& classes, bool surface, bool haptic, bool tumour)
{
  std::string csv = "frame,time,tip_x,tip_y,tip_z,nearest_class,nearest_mm";
  for (const auto& c : classes)
  {
    csv += "," + c + "_mm";
  }
  csv += ",danger_level,error_bound_mm,frame_ms,axis_x,axis_y,axis_z,tip_level,instrument_level,level_class,level_cause";
  for (const auto& c : classes)
  {
    csv += "," + c + "_point_x," + c + "_point_y," + c + "_point_z," + c + "_directional_mm," + c + "_inside," + c +
      "_inside_uncertain," + c + "_level";
    if (surface)
    {
      csv += "," + c + "_instrument_level," + c + "_surface_mm," + c + "_penetration_depth_mm," + c + "_penetration_volume_mm3," + c +
        "_penetration_depth_bound_mm," + c + "_penetration_volume_bound_mm3," + c + "_surface_bound_mm";
    }
  }
  if (haptic)
  {
    csv += ",haptic_force_n,haptic_x,haptic_y,haptic_z";
  }
  if (tumour)
  {
    csv += ",tumour_mm,tumour_id,tumour_point_x,tumour_point_y,tumour_point_z,margin_level,tumour_surface_mm";
  }
  csv += "\n";
  return csv;
}
} // namespace

std::string FramesCsvRow(const TrackedFrame& f, bool surface)
{
  std::string csv;
  const auto& r = f.Proximity;
  const int nearest = r.NearestIndex();
  csv += std::to_string(f.Frame) + "," + Number(f.TimeS, "%.6f") + "," + Number(f.TipMm[0]) + "," + Number(f.TipMm[1]) +
    "," + Number(f.TipMm[2]) + "," + (nearest >= 0 ? r.Classes[nearest].ClassName : "") + "," +
    (nearest >= 0 ? Number(r.Classes[nearest].DistanceMm) : "");
  for (const auto& c : r.Classes)
  {
    csv += "," + (c.InRange ? Number(c.DistanceMm) : "");
  }
  csv += std::string(",") + DangerLevelName(f.Level) + "," + Number(r.ErrorBoundMm) + "," + Number(f.FrameMs, "%.5f") +
    "," + Number(f.AxisWorld[0], "%.6f") + "," + Number(f.AxisWorld[1], "%.6f") + "," + Number(f.AxisWorld[2], "%.6f") +
    "," + DangerLevelName(f.TipLevel) + "," + (surface ? DangerLevelName(f.InstrumentLevel) : "") + "," +
    (f.LevelClass >= 0 ? r.Classes[static_cast<std::size_t>(f.LevelClass)].ClassName : "") + "," + DangerCauseName(f.LevelCause);
  for (std::size_t k = 0; k < r.Classes.size(); ++k)
  {
    const ClassProximity& c = r.Classes[k];
    for (int a = 0; a < 3; ++a)
    {
      csv += "," + (c.InRange ? Number(c.ClosestPoint[a]) : "");
    }
    csv += "," + (c.DirectionalMm ? Number(*c.DirectionalMm) : "");
    csv += "," + (c.InRange && c.Inside ? std::string(*c.Inside ? "1" : "0") : "");
    csv += "," + (c.InRange ? std::string(c.InsideUncertain ? "1" : "0") : "");
    csv += std::string(",") + DangerLevelName(f.ClassLevels[k]);
    if (surface)
    {
      csv += std::string(",") + (k < f.InstrumentClassLevels.size() ? DangerLevelName(f.InstrumentClassLevels[k]) : "");
      csv += "," + (f.Surface[k].InRange ? Number(f.Surface[k].DistanceMm) : "");
      // Empty where it cannot be known (an open surface has no inside), never a silent 0.
      const bool known = k < f.Penetrations.size() && f.Penetrations[k].Known;
      const Penetration none;
      const Penetration& p = known ? f.Penetrations[k] : none;
      for (double v : { p.DepthMm, p.VolumeMm3, p.DepthBoundMm, p.VolumeBoundMm3 })
      {
        csv += "," + (known ? Number(v) : "");
      }
      csv += "," + (f.Surface[k].InRange ? Number(f.Surface[k].ErrorBoundMm) : "");
    }
  }
  if (f.Haptic)
  {
    csv += "," + Number(f.Haptic->ForceN) + "," + Number(f.Haptic->Direction[0], "%.6f") + "," +
      Number(f.Haptic->Direction[1], "%.6f") + "," + Number(f.Haptic->Direction[2], "%.6f");
  }
  if (f.Tumour && f.Tumour->Worst >= 0)
  {
    const TumourProximity& t = f.Tumour->Tumours[f.Tumour->Worst];
    csv += "," + Number(t.SignedMm) + "," + t.Id + "," + Number(t.ClosestPoint[0]) + "," + Number(t.ClosestPoint[1]) + "," +
      Number(t.ClosestPoint[2]) + "," + MarginLevelName(f.Tumour->Level) + "," + (t.SurfaceKnown ? Number(t.SurfaceMm) : "");
  }
  csv += "\n";
  return csv;
}
} // namespace vp
