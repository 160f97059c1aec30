#include "vpDistancePlotRecorder.h"

#include "vpDangerBands.h"
#include "vpDistancePlot.h"
#include "vpPlotValues.h"

#include <cmath>

namespace vp
{
void DistancePlotRecorder::Fold(Extreme& e, const Extreme& later)
{
  // NaN (no value) never wins, and is replaced by any value.
  if (std::isfinite(later.LowMm) && !(later.LowMm >= e.LowMm))
  {
    e.LowMm = later.LowMm;
    e.LowAtS = later.LowAtS;
  }
  if (std::isfinite(later.HighMm) && !(later.HighMm <= e.HighMm))
  {
    e.HighMm = later.HighMm;
    e.HighAtS = later.HighAtS;
  }
}

DistancePlotRecorder::DistancePlotRecorder(const std::vector<std::string>& classes, bool surface)
  : Classes(classes)
  , Surface(surface)
{
}

void DistancePlotRecorder::Add(const TrackedFrame& frame)
{
  std::vector<double> values;
  for (std::size_t c = 0; c < this->Classes.size(); ++c)
  {
    values.push_back(TipPlotValueMm(frame, c));
    if (this->Surface)
    {
      values.push_back(InstrumentPlotValueMm(frame, c));
    }
  }
  if (this->Buckets.empty() || this->Buckets.back().Frames == this->Width)
  {
    Bucket fresh{ frame.TimeS, frame.TimeS, 0, {} };
    for (const double v : values)
    {
      fresh.Lines.push_back({ v, v, frame.TimeS, frame.TimeS });
    }
    fresh.Frames = 1;
    this->Buckets.push_back(std::move(fresh));
  }
  else
  {
    Bucket& last = this->Buckets.back();
    last.LastS = frame.TimeS;
    ++last.Frames;
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      Fold(last.Lines[k], { values[k], values[k], frame.TimeS, frame.TimeS });
    }
  }
  if (this->Buckets.size() < MaximumBuckets)
  {
    return;
  }
  // Full: merge neighbours in pairs, and make the buckets to come twice as wide.
  std::vector<Bucket> merged;
  merged.reserve(MaximumBuckets / 2);
  for (std::size_t b = 0; b + 1 < this->Buckets.size(); b += 2)
  {
    Bucket m = std::move(this->Buckets[b]);
    const Bucket& later = this->Buckets[b + 1];
    m.LastS = later.LastS;
    m.Frames += later.Frames;
    for (std::size_t k = 0; k < m.Lines.size(); ++k)
    {
      Fold(m.Lines[k], later.Lines[k]);
    }
    merged.push_back(std::move(m));
  }
  this->Buckets = std::move(merged);
  this->Width *= 2;
}

void DistancePlotRecorder::Samples(std::vector<double>& times, std::vector<PlotSeries>& series) const
{
  times.clear();
  series.clear();
  for (std::size_t c = 0; c < this->Classes.size(); ++c)
  {
    const Rgb colour = PlotSeriesColour(this->Classes[c], static_cast<int>(c));
    series.push_back({ this->Classes[c] + " (tip)", colour, {} });
    if (this->Surface)
    {
      series.push_back({ this->Classes[c] + " (instrument)", InstrumentColour(colour), {} });
    }
  }
  for (const Bucket& b : this->Buckets)
  {
    times.push_back(b.FirstS);
    if (b.Frames > 1)
    {
      times.push_back(b.LastS);
    }
    for (std::size_t k = 0; k < series.size(); ++k)
    {
      const Extreme& e = b.Lines[k];
      if (b.Frames == 1)
      {
        series[k].ValuesMm.push_back(e.LowMm);
        continue;
      }
      const bool lowFirst = e.LowAtS <= e.HighAtS;
      series[k].ValuesMm.push_back(lowFirst ? e.LowMm : e.HighMm);
      series[k].ValuesMm.push_back(lowFirst ? e.HighMm : e.LowMm);
    }
  }
}

void DistancePlotRecorder::Write(const std::string& fileName, const DangerThresholds& thresholds, double rangeMm) const
{
  std::vector<double> times;
  std::vector<PlotSeries> series;
  this->Samples(times, series);
  const std::vector<PlotBand> bands = DangerBands(thresholds, rangeMm, LowestValueMm(series) < 0);
  DistancePlotOptions options;
  options.Title = this->Surface ? "Tip and instrument distance to each vessel class over time (inside: below 0)"
                                : "Tip distance to each vessel class over time (inside: below 0)";
  WriteDistancePlotPng(fileName, times, series, bands, options);
}
} // namespace vp
