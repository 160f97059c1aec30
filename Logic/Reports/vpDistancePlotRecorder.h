#ifndef vpDistancePlotRecorder_h
#define vpDistancePlotRecorder_h

#include "vpDangerLevels.h"
#include "vpDistancePlot.h"
#include "vtkScalpelTrackingLogic.h"

#include <cstddef>
#include <string>
#include <vector>

namespace vp
{
/// distance.png of a tracking run, recorded frame by frame in memory that does not grow with
/// the run: per class the tip's plot value and, with the whole surface, the instrument's
/// (vp::TipPlotValueMm, InstrumentPlotValueMm), the instrument's largest penetration volume
/// written at its deepest point (vp::InstrumentVolumeNote), and with tumours the tip's signed
/// distance to each beside the resection margin.
///
/// Up to MaximumBuckets frames each frame is kept, and the plot is the frames' own. Past that,
/// neighbouring buckets of frames merge in pairs (a bucket then spans 2, 4, ... frames), and each
/// keeps per line its smallest and largest value, drawn at the bucket's first and last time in
/// the order they came. With at least MaximumBuckets / 2 buckets across a plot narrower than that
/// in pixels, a bucket is under a pixel wide, so the picture keeps every peak and every dip (a
/// breach is never smoothed away); only the order of the values inside a pixel is lost.
class DistancePlotRecorder
{
public:
  static constexpr std::size_t MaximumBuckets = 4096;

  /// tumours: the ids of the tumours whose margin is kept (each gets the tip's signed distance to
  /// it as a line, and the margin, marginMm, a dotted line of its own); empty: none.
  DistancePlotRecorder(const std::vector<std::string>& classes, bool surface, const std::vector<std::string>& tumours = {},
    double marginMm = 0.0);
  void Add(const TrackedFrame& frame);
  /// A time the tracker lost the tool: no value on any line, so the plot shows a gap there.
  void AddLost(double timeS);
  /// What the plot draws: the times and, per line (per class the tip's, solid, then with the
  /// surface the instrument's, dashed; per tumour the tip's signed distance, then the margin,
  /// dotted), a value at each.
  void Samples(std::vector<double>& timesS, std::vector<PlotSeries>& series) const;
  /// Writes the PNG: the recorded lines over the danger bands of thresholds, the axis up to the
  /// data's largest value (never below the caution threshold).
  void Write(const std::string& fileName, const DangerThresholds& thresholds) const;
  /// Frames per bucket now (1 while every frame is kept).
  std::size_t FramesPerBucket() const { return this->Width; }

private:
  struct Extreme
  {
    double LowMm, HighMm;     // NaN when the bucket has no value (out of range)
    double LowAtS, HighAtS;   // when they came
  };
  struct Bucket
  {
    double FirstS, LastS;
    std::size_t Frames;
    std::vector<Extreme> Lines;
  };
  /// A frame's (or a lost time's) bucket after the others, merging neighbours when full.
  void AddBucket(Bucket one);
  /// Appends the frames of later (the bucket after into) to into.
  static void Append(Bucket& into, const Bucket& later);
  std::vector<std::string> Classes;
  bool Surface;
  std::vector<std::string> Tumours;
  double MarginMm;
  std::size_t Width = 1;
  std::vector<Bucket> Buckets;
  std::vector<double> LargestVolumeMm3; ///< per class, over the run (the instrument line's note)
};
} // namespace vp

#endif
