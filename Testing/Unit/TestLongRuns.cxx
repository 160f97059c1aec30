// What a long tracking session keeps in memory (issue 16): running quantiles of the frame times
// and the plot's buckets, each bounded whatever the number of frames, and each honest about what
// it drops.
#include "vpDistancePlotRecorder.h"
#include "vpQuantile.h"
#include "vpRunningQuantiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace
{
TEST(RunningQuantiles, NeverBelowTheExactQuantileAndAtMostATenthOfAPercentAbove)
{
  std::mt19937 random(4);
  std::lognormal_distribution<double> frameMs(std::log(0.5), 1.0);
  vp::RunningQuantiles running;
  std::vector<double> all;
  for (int i = 0; i < 200000; ++i)
  {
    const double v = frameMs(random);
    running.Add(v);
    all.push_back(v);
  }
  for (const double q : { 0.0, 0.01, 0.5, 0.95, 0.99, 0.999 })
  {
    const double exact = vp::Quantile(all, q);
    EXPECT_GE(running.Quantile(q), exact) << q;
    EXPECT_LE(running.Quantile(q), exact * (1.0 + vp::RunningQuantiles::RelativeResolution)) << q;
  }
  EXPECT_EQ(running.Quantile(1.0), vp::Quantile(all, 1.0)) << "the maximum, exactly";
  EXPECT_EQ(running.Count(), 200000u);
  vp::RunningQuantiles empty;
  EXPECT_EQ(empty.Quantile(0.5), 0.0);
}

vp::TrackedFrame FrameAt(int i, double valueMm)
{
  vp::TrackedFrame f;
  f.Frame = i;
  f.TimeS = 0.01 * i;
  vp::ClassProximity c;
  c.ClassName = "portal_vein";
  c.InRange = !std::isnan(valueMm);
  c.Inside = valueMm < 0;
  c.DistanceMm = std::abs(valueMm);
  f.Proximity.Classes.push_back(c);
  return f;
}

// Short runs are drawn frame for frame; long ones in buckets whose lowest and highest values are
// all kept: a one-frame breach among 300,000 frames is still drawn, and so is a one-frame gap's
// neighbours, in at most 2 x MaximumBuckets samples.
TEST(DistancePlotRecorder, KeepsEveryFrameOfAShortRunAndEveryPeakAndDipOfALongOne)
{
  vp::DistancePlotRecorder shortRun({ "portal_vein" }, false);
  for (int i = 0; i < 1000; ++i)
  {
    shortRun.Add(FrameAt(i, i == 500 ? std::numeric_limits<double>::quiet_NaN() : 5.0 + std::sin(0.01 * i)));
  }
  std::vector<double> times;
  std::vector<vp::PlotSeries> series;
  shortRun.Samples(times, series);
  ASSERT_EQ(times.size(), 1000u);
  EXPECT_EQ(shortRun.FramesPerBucket(), 1u);
  EXPECT_DOUBLE_EQ(series[0].ValuesMm[10], 5.0 + std::sin(0.1));
  EXPECT_TRUE(std::isnan(series[0].ValuesMm[500])) << "a gap stays a gap";

  vp::DistancePlotRecorder longRun({ "portal_vein" }, false);
  const int frames = 300000;
  for (int i = 0; i < frames; ++i)
  {
    const double v = i == 123457 ? -0.8 : (i == 200001 ? 9.5 : 5.0 + std::sin(0.001 * i));
    longRun.Add(FrameAt(i, v));
  }
  longRun.Samples(times, series);
  EXPECT_LE(times.size(), 2 * vp::DistancePlotRecorder::MaximumBuckets);
  EXPECT_GT(longRun.FramesPerBucket(), 1u);
  double lowest = 1e9, highest = -1e9;
  for (const double v : series[0].ValuesMm)
  {
    lowest = std::min(lowest, v);
    highest = std::max(highest, v);
  }
  EXPECT_EQ(lowest, -0.8) << "the one-frame breach";
  EXPECT_EQ(highest, 9.5) << "the one-frame peak";
  EXPECT_DOUBLE_EQ(times.front(), 0.0);
  EXPECT_DOUBLE_EQ(times.back(), 0.01 * (frames - 1));
  for (std::size_t k = 1; k < times.size(); ++k)
  {
    EXPECT_LE(times[k - 1], times[k]) << k;
  }
}
} // namespace

// distance.png writes each class's largest instrument volume of the run at the instrument line's
// deepest point; a volume that could not be known (an open surface) is not one.
TEST(DistancePlotRecorder, TheInstrumentLineCarriesTheRunsLargestVolume)
{
  vp::DistancePlotRecorder recorder({ "portal_vein", "hepatic_vein" }, true);
  const double volumes[] = { 0.0, 2.0, 4.54, 1.0, 0.0 };
  for (int i = 0; i < 5; ++i)
  {
    vp::TrackedFrame f = FrameAt(i, 1.0);
    f.Proximity.Classes.resize(2);
    f.Surface.resize(2);
    f.Surface[0].InRange = f.Surface[1].InRange = true;
    f.Penetrations.resize(2);
    f.Penetrations[0].DepthMm = volumes[i] > 0 ? 0.5 : 0.0;
    f.Penetrations[0].VolumeMm3 = volumes[i];
    f.Penetrations[1].Known = false;
    f.Penetrations[1].VolumeMm3 = 9.0;
    recorder.Add(f);
  }
  std::vector<double> times;
  std::vector<vp::PlotSeries> series;
  recorder.Samples(times, series);
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[0].DeepestNote, "") << "the tip's line";
  EXPECT_EQ(series[1].Name, "portal_vein (instrument)");
  EXPECT_EQ(series[1].DeepestNote, "up to 4.5 mm^3 in");
  EXPECT_EQ(series[1].ValuesMm[2], -0.5);
  EXPECT_EQ(series[3].DeepestNote, "") << "an unknown volume is no volume";
}
