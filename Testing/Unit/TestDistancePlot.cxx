// Distance-over-time plot: numbers read off the rendered pixels (bands where their millimetres
// are, lines where their values are, nothing in a NaN gap), headless text, and the PNG file.
#include "vpDangerBands.h"
#include "vpDistancePlot.h"
#include "vpDistancePlotRecorder.h"
#include "vpPlotValues.h"
#include "vpInputError.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <dirent.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <tuple>

namespace
{
const vp::Rgb Red = { 220, 20, 20 };
const vp::Rgb DangerBlue = { 150, 180, 255 };
const vp::Rgb WarningGray = { 120, 120, 120 };
const vp::Rgb CautionGray = { 225, 225, 225 };
const vp::Rgb SafeCream = { 250, 250, 235 }; // not white, so it is told apart from the background

std::vector<vp::PlotBand> DangerBands()
{
  return { { 10, INFINITY, SafeCream, "safe" }, { 5, 10, CautionGray, "caution" }, { 2, 5, WarningGray, "warning" },
    { 0, 2, DangerBlue, "danger" } };
}

/// 30 frames, 1 s apart; the vessel at 4 mm except frames 10..19, where it is out of range.
struct GappedSeries
{
  std::vector<double> Times;
  vp::PlotSeries Series{ "portal_vein", Red, {} };
  GappedSeries()
  {
    for (int i = 0; i < 30; ++i)
    {
      this->Times.push_back(i);
      this->Series.ValuesMm.push_back(i >= 10 && i < 20 ? NAN : 4.0);
    }
  }
};

vp::DistancePlotOptions Options(int width = 800, int height = 400, double yMax = 20)
{
  vp::DistancePlotOptions options;
  options.WidthPx = width;
  options.HeightPx = height;
  options.Title = "tip to vessel";
  options.YMaxMm = yMax;
  return options;
}

// Outside the image: a colour no test looks for, so a wrong position fails instead of crashing.
vp::Rgb Pixel(vtkImageData* image, int x, int y)
{
  const int* dims = image->GetDimensions();
  if (x < 0 || y < 0 || x >= dims[0] || y >= dims[1])
  {
    return { 1, 2, 3 };
  }
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer(x, y, 0));
  return { p[0], p[1], p[2] };
}

int Count(vtkImageData* image, int x0, int y0, int x1, int y1, const std::function<bool(const vp::Rgb&)>& match)
{
  int count = 0;
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      count += match(Pixel(image, x, y)) ? 1 : 0;
    }
  }
  return count;
}

bool IsRed(const vp::Rgb& c)
{
  return c == Red;
}

// Also the antialiased edge pixels, a blend of the red with whatever is under it.
bool IsReddish(const vp::Rgb& c)
{
  return c[0] > c[1] + 40 && c[0] > c[2] + 40;
}

bool IsDark(const vp::Rgb& c)
{
  return c[0] < 100 && c[1] < 100 && c[2] < 100;
}

int Round(double pixel)
{
  return static_cast<int>(std::lround(pixel));
}

std::vector<std::string> FolderEntries(const std::string& dir)
{
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str()))
  {
    while (dirent* entry = readdir(d))
    {
      if (std::strcmp(entry->d_name, ".") != 0 && std::strcmp(entry->d_name, "..") != 0)
      {
        names.push_back(entry->d_name);
      }
    }
    closedir(d);
  }
  return names;
}
} // namespace

TEST(DistancePlot, ImageHasTheRequestedSizeAndRgbPixels)
{
  const GappedSeries data;
  for (const auto& size : { std::make_pair(1200, 600), std::make_pair(333, 217) })
  {
    vp::DistancePlotFrame frame;
    const auto image =
      vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), Options(size.first, size.second), &frame);
    int dims[3];
    image->GetDimensions(dims);
    EXPECT_EQ(dims[0], size.first);
    EXPECT_EQ(dims[1], size.second);
    EXPECT_EQ(dims[2], 1);
    EXPECT_EQ(image->GetScalarType(), VTK_UNSIGNED_CHAR);
    EXPECT_EQ(image->GetNumberOfScalarComponents(), 3);
    EXPECT_GT(frame.LeftPx, 0);
    EXPECT_LT(frame.LeftPx, frame.RightPx);
    EXPECT_LT(frame.RightPx, size.first - 1);
    EXPECT_GT(frame.BottomPx, 0);
    EXPECT_LT(frame.BottomPx, frame.TopPx);
    EXPECT_LT(frame.TopPx, size.second - 1);
  }
}

TEST(DistancePlot, BandsFillTheirRangeInsideThePlotAreaOnly)
{
  const GappedSeries data;
  vp::DistancePlotFrame frame;
  const auto image = vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), Options(), &frame);
  const int x = Round(frame.XOf(15)); // in the NaN gap: no line there
  EXPECT_EQ(Pixel(image, x, Round(frame.YOf(1))), DangerBlue);
  EXPECT_EQ(Pixel(image, x, Round(frame.YOf(3.5))), WarningGray);
  EXPECT_EQ(Pixel(image, x, Round(frame.YOf(7.5))), CautionGray);
  EXPECT_EQ(Pixel(image, x, Round(frame.YOf(15))), SafeCream);
  // Row 0 is the bottom row: the danger band lies in the lower half of the image.
  EXPECT_LT(Round(frame.YOf(1)), image->GetDimensions()[1] / 2);
  EXPECT_GT(Round(frame.YOf(15)), image->GetDimensions()[1] / 2);
  // Clipped: nothing of the bands left of, below or above the plot area (the safe band is open-ended).
  EXPECT_NE(Pixel(image, frame.LeftPx - 3, Round(frame.YOf(1))), DangerBlue);
  EXPECT_EQ(Count(image, x, 0, x, frame.BottomPx - 1, [](const vp::Rgb& c) { return c == DangerBlue; }), 0);
  EXPECT_EQ(Count(image, x, frame.TopPx + 1, x, image->GetDimensions()[1] - 1,
              [](const vp::Rgb& c) { return c == SafeCream; }),
    0);
}

TEST(DistancePlot, SeriesIsDrawnAtItsValuesAndInTheLegend)
{
  const GappedSeries data;
  vp::DistancePlotFrame frame;
  const auto image = vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), Options(), &frame);
  const int x = Round(frame.XOf(5)), y = Round(frame.YOf(4));
  EXPECT_GT(Count(image, x, y - 1, x, y + 1, IsRed), 0);
  // 2 px wide: a pixel centre 2 px from the nearest one is at least 1.5 px from the line's axis.
  EXPECT_EQ(Count(image, x, frame.BottomPx, x, y - 2, IsReddish), 0);
  EXPECT_EQ(Count(image, x, y + 2, x, frame.TopPx, IsReddish), 0);
  EXPECT_EQ(Pixel(image, x, Round(frame.YOf(3))), WarningGray);
  // The legend, right of the plot area, shows the series' colour.
  EXPECT_GT(Count(image, frame.RightPx + 2, 0, image->GetDimensions()[0] - 1, image->GetDimensions()[1] - 1, IsRed), 0);
}

// A penetration is a negative distance: the axis goes below zero, a line marks the vessel wall at
// 0, and the values inside are drawn under it; data that never goes below 0 keeps the axis at 0.
TEST(DistancePlot, PenetrationIsDrawnBelowTheZeroLine)
{
  std::vector<double> times;
  vp::PlotSeries series{ "portal_vein (tip)", Red, {} };
  for (int i = 0; i < 30; ++i)
  {
    times.push_back(i);
    series.ValuesMm.push_back(i < 10 ? 6.0 : i < 20 ? -3.0 : 6.0); // 3 mm inside from 10 s to 19 s
  }
  vp::DistancePlotFrame frame;
  auto bands = DangerBands();
  bands.push_back({ -INFINITY, 0, { 255, 0, 255 }, "breach" });
  const auto image = vp::RenderDistancePlot(times, { series }, bands, Options(), &frame);
  EXPECT_LT(frame.YMinMm, -3.0);
  EXPECT_GE(frame.YMinMm, -5.0) << "a tick below the lowest value, not more";
  const int zero = static_cast<int>(std::lround(frame.YOf(0.0)));
  EXPECT_GT(zero, frame.BottomPx + 5) << "the zero line is above the bottom of the plot";
  // At 15 s the line is at -3 mm: below the zero line, in the series colour, over the breach band.
  const int x = static_cast<int>(std::lround(frame.XOf(15)));
  const int y = static_cast<int>(std::lround(frame.YOf(-3.0)));
  EXPECT_LT(y, zero);
  EXPECT_EQ(Pixel(image, x, y), Red);
  EXPECT_EQ(Pixel(image, x, (y + frame.BottomPx) / 2), (vp::Rgb{ 255, 0, 255 })) << "the breach band below zero";
  EXPECT_EQ(Pixel(image, static_cast<int>(std::lround(frame.XOf(5))), zero), (vp::Rgb{ 60, 60, 60 })) << "the zero line";
  // At 5 s, +6 mm: above the zero line.
  EXPECT_EQ(Pixel(image, static_cast<int>(std::lround(frame.XOf(5))), static_cast<int>(std::lround(frame.YOf(6.0)))), Red);

  // Nothing below zero: the axis starts at 0 as before.
  vp::DistancePlotFrame positive;
  GappedSeries gapped;
  vp::RenderDistancePlot(gapped.Times, { gapped.Series }, DangerBands(), Options(), &positive);
  EXPECT_EQ(positive.YMinMm, 0.0);
}


// Every class's tip and instrument colour, drawn across every danger band the reports use (the
// artery's red on the breach band, the portal vein's blue on the danger band), stands out from
// the band: across the line, some pixel contrasts with the band by WCAG's 3:1 for graphics.
TEST(DistancePlot, LinesAreReadableOnEveryDangerBand)
{
  const auto bands = vp::DangerBands(vp::DangerThresholds{}, true);
  std::vector<vp::PlotSeries> all;
  int index = 0;
  for (const char* name : { "portal_vein", "hepatic_artery", "hepatic_vein", "other" })
  {
    const vp::Rgb colour = vp::ClassDisplayColour(name, index++);
    all.push_back({ std::string(name) + " (tip)", colour, {} });
    all.push_back({ std::string(name) + " (instrument)", vp::InstrumentColour(colour), {} });
  }
  for (const vp::PlotBand& band : bands)
  {
    const double valueMm = std::isfinite(band.FromMm) && std::isfinite(band.ToMm) ? 0.5 * (band.FromMm + band.ToMm)
      : std::isfinite(band.FromMm) ? band.FromMm + 3.0 : band.ToMm - 1.5;
    for (const vp::PlotSeries& colour : all)
    {
      vp::PlotSeries series = colour;
      std::vector<double> times;
      for (int i = 0; i < 10; ++i)
      {
        times.push_back(i);
        series.ValuesMm.push_back(valueMm);
      }
      vp::DistancePlotFrame frame;
      auto options = Options();
      options.YMinMm = -4.0;
      const auto image = vp::RenderDistancePlot(times, { series }, bands, options, &frame);
      const int x = Round(frame.XOf(5)), y = Round(frame.YOf(valueMm));
      ASSERT_EQ(Pixel(image, x, y + 12), band.Colour) << band.Label << ": the band around the line";
      double best = 0;
      for (int dy = -4; dy <= 4; ++dy)
      {
        best = std::max(best, vp::ContrastRatio(Pixel(image, x, y + dy), band.Colour));
      }
      EXPECT_GE(best, 3.0) << series.Name << " on the " << band.Label << " band";
    }
  }
}

// What both plots draw for a frame: the tip's distance or minus its depth inside, the instrument's
// distance or minus its penetration depth, gaps where nothing is known.
TEST(DistancePlot, PlotValuesAreSignedDistancesWithGaps)
{
  vp::TrackedFrame f;
  f.Proximity.Classes.resize(3);
  f.Proximity.Classes[0].InRange = true;
  f.Proximity.Classes[0].DistanceMm = 0.6;
  f.Proximity.Classes[0].Inside = true;
  f.Proximity.Classes[1].InRange = true;
  f.Proximity.Classes[1].DistanceMm = 3.3;
  f.Proximity.Classes[1].Inside = false;
  EXPECT_EQ(vp::TipPlotValueMm(f, 0), -0.6);
  EXPECT_EQ(vp::TipPlotValueMm(f, 1), 3.3);
  EXPECT_TRUE(std::isnan(vp::TipPlotValueMm(f, 2))) << "out of range: a gap";
  EXPECT_TRUE(std::isnan(vp::InstrumentPlotValueMm(f, 0))) << "the instrument not measured: a gap";
  f.Surface.resize(3);
  f.Surface[0].InRange = true; // touching
  f.Surface[1].InRange = true;
  f.Surface[1].DistanceMm = 2.6;
  f.Penetrations.resize(3);
  f.Penetrations[0].DepthMm = 1.02;
  f.Penetrations[0].VolumeMm3 = 3.7;
  f.Penetrations[2].Known = false;
  EXPECT_EQ(vp::InstrumentPlotValueMm(f, 0), -1.02);
  EXPECT_EQ(vp::InstrumentPlotValueMm(f, 1), 2.6);
  EXPECT_TRUE(std::isnan(vp::InstrumentPlotValueMm(f, 2)));
  const vp::Rgb light = vp::InstrumentColour({ 0, 150, 200 });
  EXPECT_EQ(light, (vp::Rgb{ 170, 220, 236 }));
}

TEST(DistancePlot, ValuesBeyondTheAxisAreCutAtThePlotArea)
{
  vp::DistancePlotFrame frame;
  const auto image =
    vp::RenderDistancePlot({ 0, 1, 2 }, { { "vein", Red, { 30, 30, 30 } } }, DangerBands(), Options(800, 400, 20), &frame);
  EXPECT_EQ(Count(image, frame.LeftPx, frame.TopPx + 1, frame.RightPx, image->GetDimensions()[1] - 1, IsReddish), 0);
  // A line from 40 mm down to 0 mm enters the plot area at its top edge.
  const auto falling =
    vp::RenderDistancePlot({ 0, 1 }, { { "vein", Red, { 40, 0 } } }, DangerBands(), Options(800, 400, 20), &frame);
  EXPECT_EQ(Count(falling, frame.LeftPx, frame.TopPx + 1, frame.RightPx, falling->GetDimensions()[1] - 1, IsReddish), 0);
  const int x = Round(frame.XOf(0.5)); // the line is at 20 mm there, the top of the axis
  EXPECT_GT(Count(falling, x - 2, frame.TopPx - 3, x + 2, frame.TopPx, IsRed), 0);
}

TEST(DistancePlot, NaNValuesLeaveAGap)
{
  const GappedSeries data;
  vp::DistancePlotFrame frame;
  const auto image = vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), Options(), &frame);
  // Last value at t = 9, next at t = 20; the line's half width and antialiasing reach 2 px.
  const int gapFrom = Round(frame.XOf(9)) + 3, gapTo = Round(frame.XOf(20)) - 3;
  ASSERT_LT(gapFrom, gapTo);
  EXPECT_EQ(Count(image, gapFrom, frame.BottomPx, gapTo, frame.TopPx, IsReddish), 0);
  EXPECT_GT(Count(image, Round(frame.XOf(2)), frame.BottomPx, Round(frame.XOf(7)), frame.TopPx, IsRed), 0);
  EXPECT_GT(Count(image, Round(frame.XOf(22)), frame.BottomPx, Round(frame.XOf(27)), frame.TopPx, IsRed), 0);
}

TEST(DistancePlot, LoneSampleIsDrawnAsADot)
{
  vp::DistancePlotFrame frame;
  const auto between = vp::RenderDistancePlot(
    { 0, 1, 2 }, { { "artery", Red, { NAN, 4, NAN } } }, DangerBands(), Options(), &frame);
  int x = Round(frame.XOf(1)), y = Round(frame.YOf(4));
  EXPECT_GT(Count(between, x - 1, y - 1, x + 1, y + 1, IsRed), 0);
  EXPECT_EQ(Count(between, frame.LeftPx, frame.BottomPx, frame.RightPx, frame.TopPx, IsReddish),
    Count(between, x - 4, y - 4, x + 4, y + 4, IsReddish));

  const auto single = vp::RenderDistancePlot({ 5 }, { { "artery", Red, { 4 } } }, DangerBands(), Options(), &frame);
  EXPECT_LT(frame.TimeMinS, 5);
  EXPECT_GT(frame.TimeMaxS, 5);
  x = Round(frame.XOf(5));
  y = Round(frame.YOf(4));
  EXPECT_GT(x, frame.LeftPx);
  EXPECT_LT(x, frame.RightPx);
  EXPECT_GT(Count(single, x - 1, y - 1, x + 1, y + 1, IsRed), 0);
}

TEST(DistancePlot, DegenerateInputsStillRender)
{
  vp::DistancePlotFrame frame;
  const auto empty = vp::RenderDistancePlot({}, {}, {}, Options(300, 200, 0), &frame);
  EXPECT_EQ(empty->GetDimensions()[0], 300);
  EXPECT_GT(frame.TimeMaxS, frame.TimeMinS);
  EXPECT_GT(frame.YMaxMm, 0);

  const auto allNaN =
    vp::RenderDistancePlot({ 0, 1, 2 }, { { "vein", Red, { NAN, NAN, NAN } } }, DangerBands(), Options(), &frame);
  EXPECT_EQ(Count(allNaN, frame.LeftPx, frame.BottomPx, frame.RightPx, frame.TopPx, IsReddish), 0);

  const auto zeroSpan =
    vp::RenderDistancePlot({ 2, 2 }, { { "vein", Red, { 3, 3 } } }, DangerBands(), Options(), &frame);
  EXPECT_DOUBLE_EQ(frame.TimeMaxS - frame.TimeMinS, 1.0);
  EXPECT_GT(Count(zeroSpan, Round(frame.XOf(2)) - 2, Round(frame.YOf(3)) - 2, Round(frame.XOf(2)) + 2,
              Round(frame.YOf(3)) + 2, IsRed),
    0);
}

TEST(DistancePlot, MismatchedSeriesLengthIsRefused)
{
  EXPECT_THROW(vp::RenderDistancePlot({ 0, 1, 2 }, { { "vein", Red, { 3, 3 } } }, {}, Options()), std::invalid_argument);
  EXPECT_THROW(vp::RenderDistancePlot({}, {}, {}, Options(0, 100)), std::invalid_argument);
}

TEST(DistancePlot, AutomaticYAxisCoversTheDataAndEveryBand)
{
  vp::DistancePlotFrame frame;
  vp::RenderDistancePlot({ 0, 1 }, { { "vein", Red, { 3, 37 } } }, DangerBands(), Options(800, 400, 0), &frame);
  EXPECT_GE(frame.YMaxMm, 37);
  EXPECT_LE(frame.YMaxMm, 50);
  vp::RenderDistancePlot({ 0, 1 }, { { "vein", Red, { 3, 1 } } }, DangerBands(), Options(800, 400, 0), &frame);
  EXPECT_GT(frame.YMaxMm, 10); // above the safe band's lower edge, so the band shows
  vp::RenderDistancePlot({ 0, 1 }, { { "vein", Red, { 3, 37 } } }, DangerBands(), Options(800, 400, 25), &frame);
  EXPECT_EQ(frame.YMaxMm, 25);
}

// The report's axis follows the data, every threshold in view (issue 34: a run within 5 mm was a
// flat line at the bottom of a 0-55 mm axis, fixed by the engine's 50 mm range).
TEST(DistancePlot, TheReportsAxisFollowsTheDataWithEveryThresholdInView)
{
  const vp::DangerThresholds thresholds;
  const auto bands = vp::DangerBands(thresholds);
  vp::DistancePlotFrame frame;
  vp::RenderDistancePlot({ 0, 1, 2 }, { { "vein", Red, { 4.5, 3.0, 4.0 } } }, bands, Options(800, 400, 0), &frame);
  EXPECT_GT(frame.YMaxMm, thresholds.CautionMm) << "the caution threshold stays in view";
  EXPECT_LE(frame.YMaxMm, 15.0) << "the data fill the plot";
  vp::RenderDistancePlot({ 0, 1 }, { { "vein", Red, { 3, 37 } } }, bands, Options(800, 400, 0), &frame);
  EXPECT_GE(frame.YMaxMm, 37);
  EXPECT_LE(frame.YMaxMm, 45);
  EXPECT_TRUE(std::isinf(bands.back().ToMm)) << "the safe band is open-ended";
}

TEST(DistancePlot, NiceTickStepIsOneTwoOrFiveTimesAPowerOfTen)
{
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(10, 5), 2);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(7.3, 5), 2);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(60, 14), 5);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(1234, 6), 500);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(0.37, 4), 0.1);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(0.9, 1), 1);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(0, 5), 1);
  EXPECT_DOUBLE_EQ(vp::NiceTickStep(NAN, 5), 1);
}

TEST(DistancePlot, TextIsRenderedWithoutADisplay)
{
  unsetenv("DISPLAY"); // the command-line tool runs headless; FreeType must not need X
  const GappedSeries data;
  vp::DistancePlotFrame frame;
  vp::DistancePlotOptions options = Options();
  const auto titled = vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), options, &frame);
  const int width = options.WidthPx, height = options.HeightPx;
  // Above the plot area, between its sides: only the title (the top y tick label is left of it).
  EXPECT_GT(Count(titled, frame.LeftPx, frame.TopPx + 2, frame.RightPx, height - 1, IsDark), 20);
  EXPECT_GT(Count(titled, 0, 0, width - 1, frame.BottomPx - 8, IsDark), 20);              // x ticks, x label
  EXPECT_GT(Count(titled, 0, frame.BottomPx, frame.LeftPx - 8, frame.TopPx, IsDark), 20); // y ticks, y label
  options.Title.clear();
  const auto untitled = vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), options, &frame);
  EXPECT_EQ(Count(untitled, frame.LeftPx, frame.TopPx + 2, frame.RightPx, height - 1, IsDark), 0);
}

TEST(DistancePlot, WrittenPngReadsBackUnchanged)
{
  const GappedSeries data;
  const std::string dir = vp::test::MakeTempDir("plot");
  const std::string path = dir + "/distance.png";
  vp::WriteDistancePlotPng(path, data.Times, { data.Series }, DangerBands(), Options(640, 360));
  EXPECT_EQ(FolderEntries(dir), std::vector<std::string>{ "distance.png" }); // no temporary left behind

  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* read = reader->GetOutput();
  ASSERT_EQ(read->GetDimensions()[0], 640);
  ASSERT_EQ(read->GetDimensions()[1], 360);
  ASSERT_EQ(read->GetNumberOfScalarComponents(), 3);
  const auto rendered = vp::RenderDistancePlot(data.Times, { data.Series }, DangerBands(), Options(640, 360));
  auto* readPixels = vtkUnsignedCharArray::SafeDownCast(read->GetPointData()->GetScalars());
  ASSERT_NE(readPixels, nullptr);
  EXPECT_EQ(std::memcmp(readPixels->GetPointer(0), rendered->GetScalarPointer(), 640 * 360 * 3), 0);
}

TEST(DistancePlot, UnwritableFolderThrowsAndLeavesNoFile)
{
  const GappedSeries data;
  const std::string dir = vp::test::MakeTempDir("plotbad");
  const std::string path = dir + "/missing/distance.png";
  try
  {
    vp::WriteDistancePlotPng(path, data.Times, { data.Series }, DangerBands(), Options());
    ADD_FAILURE() << "no error for " << path;
  }
  catch (const vp::InputError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": cannot write:", 0), 0u) << e.what();
  }
  EXPECT_FALSE(vp::test::FileExists(path));
  EXPECT_TRUE(FolderEntries(dir).empty());
}

// Issue 31: where the tracker lost the tool, the plot shows a gap: no value on any line at that
// time, the values before and after as they were.
TEST(DistancePlotRecorder, ALostPoseIsAGapOnEveryLine)
{
  vp::DistancePlotRecorder recorder({ "portal_vein" }, false);
  auto frame = [](double t, double mm) {
    vp::TrackedFrame f;
    f.TimeS = t;
    vp::ClassProximity c;
    c.ClassName = "portal_vein";
    c.InRange = true;
    c.DistanceMm = mm;
    c.Inside = false;
    f.Proximity.Classes.push_back(c);
    return f;
  };
  recorder.Add(frame(0.0, 12.0));
  recorder.AddLost(0.1);
  recorder.Add(frame(0.2, 8.0));
  std::vector<double> times;
  std::vector<vp::PlotSeries> series;
  recorder.Samples(times, series);
  ASSERT_EQ(series.size(), 1u);
  ASSERT_EQ(times.size(), 3u);
  EXPECT_EQ(times[1], 0.1);
  EXPECT_TRUE(std::isnan(series[0].ValuesMm[1])) << "a gap, not a value carried over";
  EXPECT_FALSE(std::isnan(series[0].ValuesMm[0]));
  EXPECT_FALSE(std::isnan(series[0].ValuesMm[2]));
}

// distance.png tells the instrument from the tip by its dashes, and with tumours carries the tip's
// signed distance to each and the margin, dotted.
TEST(DistancePlotRecorder, TheInstrumentIsDashedAndATumourHasItsLineAndItsMargin)
{
  vp::DistancePlotRecorder recorder({ "portal_vein" }, true, { "03" }, 5.0);
  for (int k = 0; k < 3; ++k)
  {
    vp::TrackedFrame f;
    f.TimeS = 0.1 * k;
    vp::ClassProximity c;
    c.ClassName = "portal_vein";
    c.InRange = true;
    c.DistanceMm = 12.0 - k;
    f.Proximity.Classes.push_back(c);
    f.Surface.resize(1);
    f.Surface[0].InRange = true;
    f.Surface[0].DistanceMm = 9.0 - k;
    f.Tumour.emplace();
    f.Tumour->Tumours.resize(1);
    f.Tumour->Tumours[0].Id = "03";
    f.Tumour->Tumours[0].SignedMm = 2.0 - 2.0 * k; // into the tumour by the last frame
    recorder.Add(f);
  }
  std::vector<double> times;
  std::vector<vp::PlotSeries> series;
  recorder.Samples(times, series);
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[0].Name, "portal_vein (tip)");
  EXPECT_EQ(series[0].Style, vp::LineStyle::Solid);
  EXPECT_EQ(series[1].Name, "portal_vein (instrument)");
  EXPECT_EQ(series[1].Style, vp::LineStyle::Dashed);
  EXPECT_EQ(series[2].Name, "tumour 03 (tip)");
  EXPECT_EQ(series[2].ValuesMm, (std::vector<double>{ 2.0, 0.0, -2.0 }));
  EXPECT_EQ(series[3].Name, "margin (5 mm)");
  EXPECT_EQ(series[3].Style, vp::LineStyle::Dotted);
  EXPECT_EQ(series[3].ValuesMm, (std::vector<double>{ 5.0, 5.0, 5.0 }));
}

// A dashed line is drawn on about 70 % of its length (10 px on, 8 off, each dash's round ends a
// line's width more), a dotted one on about half (dots of 4 px, 3 apart), a solid one all along.
TEST(DistancePlot, DashedAndDottedLinesLeaveGaps)
{
  const std::vector<double> times = { 0.0, 10.0 };
  for (const auto& [style, low, high] : { std::tuple<vp::LineStyle, double, double>{ vp::LineStyle::Solid, 0.98, 1.0 },
         { vp::LineStyle::Dashed, 0.6, 0.8 }, { vp::LineStyle::Dotted, 0.4, 0.65 } })
  {
    vp::PlotSeries s{ "level", Red, { 4.0, 4.0 } };
    s.Style = style;
    vp::DistancePlotFrame frame;
    const auto image = vp::RenderDistancePlot(times, { s }, DangerBands(), Options(), &frame);
    const int y = Round(frame.YOf(4.0));
    const int x0 = frame.LeftPx + 4, x1 = frame.RightPx - 4;
    const double share = Count(image, x0, y, x1, y, IsReddish) / static_cast<double>(x1 - x0 + 1);
    EXPECT_GE(share, low) << static_cast<int>(style);
    EXPECT_LE(share, high) << static_cast<int>(style);
  }
}

// Cases are not a continuum: on a category axis each case's value is its own mark, and nothing
// of the series lies between two cases (a line from 2 mm to 12 mm would cross the gap's middle).
TEST(DistancePlot, ACategoryAxisMarksEachCaseAndJoinsNone)
{
  auto options = Options();
  options.XTickLabels = { "case-a", "case-b", "case-c" };
  for (const vp::LineStyle style : { vp::LineStyle::Solid, vp::LineStyle::Dashed, vp::LineStyle::Dotted })
  {
    vp::PlotSeries s{ "portal_vein", Red, { 2.0, 12.0, 4.0 } };
    s.Style = style;
    vp::DistancePlotFrame frame;
    const auto image = vp::RenderDistancePlot({ 1, 2, 3 }, { s }, DangerBands(), options, &frame);
    for (int k = 1; k <= 3; ++k)
    {
      const int x = Round(frame.XOf(k)), y = Round(frame.YOf(s.ValuesMm[static_cast<std::size_t>(k - 1)]));
      EXPECT_GT(Count(image, x - 1, y - 1, x + 1, y + 1, IsRed), 0) << "case " << k << ", style " << static_cast<int>(style);
    }
    // The middle of each gap between two cases' slots, over the whole height: no series there.
    for (const double middle : { 1.5, 2.5 })
    {
      const int x = Round(frame.XOf(middle));
      EXPECT_EQ(Count(image, x - 2, frame.BottomPx, x + 2, frame.TopPx, IsReddish), 0)
        << "between cases at " << middle << ", style " << static_cast<int>(style);
    }
  }
}

// An inset that must show its whole legend grows as far as the legend needs; without the option
// the size is as given and a long legend is cut.
TEST(DistancePlot, AnImageGrowsToFitItsLegendWhenAsked)
{
  const auto bands = vp::DangerBands(vp::DangerThresholds{}, true);
  std::vector<vp::PlotSeries> series;
  for (const char* name : { "portal_vein (instrument)", "hepatic_artery (instrument)", "hepatic_vein (instrument)" })
  {
    series.push_back({ name, Red, { 3, 4 } });
  }
  vp::DistancePlotFrame frame;
  auto options = Options(300, 150);
  const auto cut = vp::RenderDistancePlot({ 0, 1 }, series, bands, options, &frame);
  EXPECT_FALSE(frame.LegendWhole);
  int dims[3];
  cut->GetDimensions(dims);
  EXPECT_EQ(dims[0], 300);
  EXPECT_EQ(dims[1], 150);
  options.GrowToFitLegend = true;
  const auto grown = vp::RenderDistancePlot({ 0, 1 }, series, bands, options, &frame);
  EXPECT_TRUE(frame.LegendWhole);
  grown->GetDimensions(dims);
  EXPECT_GT(dims[0], 300);
  EXPECT_GT(dims[1], 150);
}
