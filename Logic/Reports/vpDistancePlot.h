#ifndef vpDistancePlot_h
#define vpDistancePlot_h

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

/// Distance over time per vessel class, over the danger bands, as a PNG. Rasterised here (FreeType
/// for the text) rather than through a vtkRenderWindow, because the command-line tool that writes
/// these reports runs on machines without a display or an OpenGL context.
namespace vp
{
using Rgb = std::array<unsigned char, 3>;

/// How a line is drawn: solid (the tip), dashed (the whole instrument), dotted (a reference
/// level such as the resection margin), so that lines differ by more than their shade.
enum class LineStyle
{
  Solid,
  Dashed,
  Dotted
};

struct PlotSeries
{
  std::string Name;
  Rgb Colour;
  /// One value per time. NaN (any non-finite value) means "no value" (vessel out of range, tool
  /// not tracked) and leaves a gap rather than a line through it.
  std::vector<double> ValuesMm;
  /// Written beside the line's lowest value when that is below zero (the instrument's largest
  /// penetration volume); empty: nothing.
  std::string DeepestNote = {};
  LineStyle Style = LineStyle::Solid;
};

/// A horizontal background band (a danger level), drawn under the lines. ToMm may be +infinity
/// for the open-ended "safe" band (the legend then shows "> FromMm"), FromMm -infinity for one
/// below zero ("< ToMm": inside a vessel).
struct PlotBand
{
  double FromMm;
  double ToMm;
  Rgb Colour;
  std::string Label;
};

struct DistancePlotOptions
{
  int WidthPx = 1200;
  int HeightPx = 600;
  std::string Title;
  std::string XLabel = "time (s)";
  std::string YLabel = "distance (mm)";
  /// Top of the y axis. 0: from the data, and at least the highest finite band edge, so every
  /// band shows even when the tool never came near it.
  double YMaxMm = 0;
  /// Bottom of the y axis: 0 (default) keeps it at 0 unless a value is negative (a penetration,
  /// drawn as a negative distance), which takes it down to a tick below the lowest value; a
  /// negative number fixes it there.
  double YMinMm = 0;
  /// When the axis goes below zero by itself (YMinMm 0), its bottom is a multiple of this (mm);
  /// 0 (default): of the tick step. A live plot sets it, so its scale moves only in whole steps.
  double YMinStepMm = 0;
  /// The image grows beyond WidthPx x HeightPx as far as its legend needs to be drawn whole (the
  /// legend takes at most 2/5 of the width, its rows hang from the plot area's top): an inset that
  /// must show every entry. Default false: the size is as given, a long legend cut.
  bool GrowToFitLegend = false;
  /// The x axis counts things (a cohort's cases, 1 to N): its ticks are whole numbers, 1 apart at
  /// the least. Default false: times, any nice step.
  bool WholeXTicks = false;
  /// A category axis (a cohort's cases by name): label k sits at x = k + 1, the axis runs from 0.5
  /// to N + 0.5 so that no point at either end is cut, and a label is shortened ("...") to the
  /// room its tick has. Each value is then a mark of its own (a dot with a bar across its slot in
  /// the series' style), not joined to the next category's. Empty (default): numbers.
  std::vector<std::string> XTickLabels;
};

/// Where the data went in the image: the plot area in vtkImageData pixel indices (row 0 at the
/// bottom), inclusive, and the ranges it spans. A viewer needs it to map the mouse back to a
/// time; the tests need it to find what was drawn where.
struct DistancePlotFrame
{
  int LeftPx = 0;
  int RightPx = 0;
  int BottomPx = 0;
  int TopPx = 0;
  double TimeMinS = 0;
  double TimeMaxS = 1;
  double YMaxMm = 1;
  double YMinMm = 0;
  /// Every legend entry was drawn whole: no name cut at the right, no row below the image.
  bool LegendWhole = true;

  /// Pixel coordinates as doubles; pixel i has its centre at i.
  double XOf(double timeS) const;
  double YOf(double distanceMm) const;
};

/// The lowest finite value of all the series, or 0 when none is below 0 (a penetration drawn as a
/// negative distance makes it negative).
double LowestValueMm(const std::vector<PlotSeries>& series);

/// WCAG 2's relative luminance of an sRGB colour (0 black to 1 white), and the contrast ratio of
/// two colours (1 to 21; 3 is WCAG's minimum for graphics). The plot's lines are rimmed by them.
double RelativeLuminance(const Rgb& colour);
double ContrastRatio(const Rgb& a, const Rgb& b);

/// Renders the plot into unsigned char RGB pixels of options.WidthPx x options.HeightPx.
/// Text is ASCII only (the embedded font has no other glyphs). Times that are not finite are
/// skipped like missing values; an empty or zero time span gets a 1 s span around it.
/// Throws std::invalid_argument when a series has not one value per time or the size is not
/// positive.
vtkSmartPointer<vtkImageData> RenderDistancePlot(const std::vector<double>& timesS,
  const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands,
  const DistancePlotOptions& options, DistancePlotFrame* frame = nullptr);

/// Renders as above and writes a PNG. The file appears whole or not at all (temporary name beside
/// it, then rename); throws vp::InputError(fileName, "cannot write: ...") when it cannot.
void WriteDistancePlotPng(const std::string& fileName, const std::vector<double>& timesS,
  const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands,
  const DistancePlotOptions& options);

/// The tick spacing for an axis of this span with at most maxTicks intervals: the smallest
/// 1, 2 or 5 x 10^k that is large enough, so tick labels are round numbers. 1 for a span that
/// is not positive and finite.
double NiceTickStep(double span, int maxTicks);
} // namespace vp

#endif
