#include "vpTrackingOptions.h"

#include "vpPointCsv.h"

namespace vp
{
DangerThresholds ParseDangerThresholds(const Arguments& args)
{
  DangerThresholds thresholds;
  if (args.Has("--danger-mm"))
  {
    const auto d = ParsePoint(args.Get("--danger-mm"), "--danger-mm");
    thresholds = { d[0], d[1], d[2] };
  }
  thresholds.Validate("--danger-mm");
  return thresholds;
}

ScalpelTipDefinition ParseTipDefinition(const Arguments& args)
{
  ScalpelTipDefinition tip;
  if (args.Has("--tip"))
  {
    tip.TipMm = ParsePoint(args.Get("--tip"), "--tip");
  }
  if (args.Has("--axis"))
  {
    tip.Axis = ParsePoint(args.Get("--axis"), "--axis");
  }
  return tip;
}
} // namespace vp
