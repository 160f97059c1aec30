#include "vpDistancePlotRecorder.h"

#include "vpClassName.h"
#include "vpDangerBands.h"
#include "vpDistancePlot.h"
#include "vpPlotValues.h"
#include "vpInputError.h"

#include <algorithm>
#include <limits>
#include <cmath>

namespace vp
{
void DistancePlotRecorder::Append(Bucket& into, const Bucket& later)
{
  into.LastS = later.LastS;
  into.Frames += later.Frames;
  for (std::size_t k = 0; k < into.Lines.size(); ++k)
  {
    // NaN (no value) never wins, and is replaced by any value.
    Extreme& e = into.Lines[k];
    const Extreme& l = later.Lines[k];
    if (std::isfinite(l.LowMm) && !(l.LowMm >= e.LowMm))
    {
      e.LowMm = l.LowMm;
      e.LowAtS = l.LowAtS;
    }
    if (std::isfinite(l.HighMm) && !(l.HighMm <= e.HighMm))
    {
      e.HighMm = l.HighMm;
      e.HighAtS = l.HighAtS;
    }
  }
}

DistancePlotRecorder::DistancePlotRecorder(
  const std::vector<std::string>& classes, bool surface, const std::vector<std::string>& tumours, double marginMm)
  : Classes(classes)
  , Surface(surface)
  , Tumours(tumours)
  , MarginMm(marginMm)
  , LargestVolumeMm3(classes.size(), 0.0)
{
}

void DistancePlotRecorder::AddLost(double timeS)
{
  const double none = std::numeric_limits<double>::quiet_NaN();
  Bucket one{ timeS, timeS, 1, {} };
  one.Lines.assign(this->Classes.size() * (this->Surface ? 2 : 1) + this->Tumours.size(), Extreme{ none, none, timeS, timeS });
  this->AddBucket(std::move(one));
}

void DistancePlotRecorder::Add(const TrackedFrame& frame)
{
  // The frame as a bucket of its own, then into the last bucket while it has room.
  const double t = frame.TimeS;
  Bucket one{ t, t, 1, {} };
  for (std::size_t c = 0; c < this->Classes.size(); ++c)
  {
    const double tip = TipPlotValueMm(frame, c);
    one.Lines.push_back({ tip, tip, t, t });
    if (this->Surface)
    {
      const double instrument = InstrumentPlotValueMm(frame, c);
      one.Lines.push_back({ instrument, instrument, t, t });
      this->LargestVolumeMm3[c] = std::max(this->LargestVolumeMm3[c], InstrumentVolumeMm3(frame, c));
    }
  }
  for (std::size_t k = 0; k < this->Tumours.size(); ++k)
  {
    const bool known = frame.Tumour && k < frame.Tumour->Tumours.size();
    const double signedMm = known ? frame.Tumour->Tumours[k].SignedMm : std::numeric_limits<double>::quiet_NaN();
    one.Lines.push_back({ signedMm, signedMm, t, t });
  }
  this->AddBucket(std::move(one));
}

void DistancePlotRecorder::AddBucket(Bucket one)
{
  if (!this->Buckets.empty() && this->Buckets.back().Frames < this->Width)
  {
    Append(this->Buckets.back(), one);
  }
  else
  {
    this->Buckets.push_back(std::move(one));
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
    merged.push_back(std::move(this->Buckets[b]));
    Append(merged.back(), this->Buckets[b + 1]);
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
    const Rgb colour = ClassDisplayColour(this->Classes[c], static_cast<int>(c));
    series.push_back({ this->Classes[c] + " (tip)", colour, {} });
    if (this->Surface)
    {
      series.push_back({ this->Classes[c] + " (instrument)", InstrumentColour(colour), {},
        InstrumentVolumeNote(this->LargestVolumeMm3[c]), LineStyle::Dashed });
    }
  }
  for (const std::string& id : this->Tumours)
  {
    series.push_back({ TumourSpoken(id) + " (tip)", TumourDisplayColour, {} });
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
  if (!this->Tumours.empty())
  {
    series.push_back({ "margin (" + FixedText(this->MarginMm, "%g") + " mm)", TumourDisplayColour,
      std::vector<double>(times.size(), this->MarginMm), {}, LineStyle::Dotted });
  }
}

void DistancePlotRecorder::Write(const std::string& fileName, const DangerThresholds& thresholds) const
{
  std::vector<double> times;
  std::vector<PlotSeries> series;
  this->Samples(times, series);
  const std::vector<PlotBand> bands = DangerBands(thresholds, LowestValueMm(series) < 0);
  DistancePlotOptions options;
  options.Title = std::string(this->Surface ? "Tip (solid) and instrument (dashed) distance to each vessel class"
                                             : "Tip distance to each vessel class") +
    (this->Tumours.empty() ? "" : " and tumour") + " over time (inside: below 0)";
  WriteDistancePlotPng(fileName, times, series, bands, options);
}
} // namespace vp
