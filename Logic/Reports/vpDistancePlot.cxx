#include "vpDistancePlot.h"

#include "vpInputError.h"
#include "vpPngFile.h"

#include <vtkFreeTypeTools.h>
#include <vtkNew.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace vp
{
namespace
{
const Rgb Black = { 0, 0, 0 };
const Rgb White = { 255, 255, 255 };
const Rgb Frame = { 60, 60, 60 };
const double LineHalfWidthPx = 1.0;   // 2 px lines
const double PointHalfWidthPx = 2.5;  // a lone sample as a 5 px dot
const double RimPx = 1.0;             // the contrasting rim each side of a line
const int TickLengthPx = 5;
const int GapPx = 6;
const int LegendSwatchPx = 24;

/// Pixel rectangle, inclusive, vtkImageData indices (y up).
struct Rect
{
  int X0, Y0, X1, Y1;
};

/// The RGB pixels being drawn on, with every write bounds-checked so that nothing drawn near an
/// edge (text, thick lines) can reach outside the buffer.
class Canvas
{
public:
  Canvas(vtkImageData* image, int width, int height)
    : Canvas(static_cast<unsigned char*>(image->GetScalarPointer()), width, height)
  {
  }
  Canvas(unsigned char* pixels, int width, int height)
    : Pixels(pixels)
    , Width(width)
    , Height(height)
  {
  }
  Rect Whole() const { return { 0, 0, this->Width - 1, this->Height - 1 }; }
  void Blend(int x, int y, const Rgb& colour, double alpha)
  {
    if (x < 0 || y < 0 || x >= this->Width || y >= this->Height || alpha <= 0)
    {
      return;
    }
    unsigned char* p = this->Pixels + 3 * (static_cast<std::size_t>(y) * this->Width + x);
    if (alpha >= 1.0)
    {
      // Opaque: the pixel is not read, so the first fill of a fresh image reads no uninitialised
      // memory (valgrind followed those bytes into every colour drawn after).
      std::copy(colour.begin(), colour.end(), p);
      return;
    }
    for (int c = 0; c < 3; ++c)
    {
      p[c] = static_cast<unsigned char>(std::lround(p[c] + (colour[c] - p[c]) * alpha));
    }
  }

  /// The colour at (x, y), clamped to the image.
  Rgb At(int x, int y) const
  {
    x = std::clamp(x, 0, this->Width - 1);
    y = std::clamp(y, 0, this->Height - 1);
    const unsigned char* p = this->Pixels + 3 * (static_cast<std::size_t>(y) * this->Width + x);
    return { p[0], p[1], p[2] };
  }
  /// A copy of the pixels, to read what lay under a drawing once it is covered.
  std::vector<unsigned char> Copy() const
  {
    return std::vector<unsigned char>(this->Pixels, this->Pixels + 3 * static_cast<std::size_t>(this->Width) * this->Height);
  }

private:
  unsigned char* Pixels;
  int Width, Height;
};

/// Black or white, whichever has the higher WCAG contrast ratio against the band under a line:
/// the rim that keeps a line readable where its own colour is close to the band's (the artery's
/// red on the magenta breach band, the hepatic vein's dark blue on the dark gray warning band).
Rgb RimColour(const Rgb& under)
{
  return ContrastRatio(under, Black) >= ContrastRatio(under, White) ? Black : White;
}

void FillRect(Canvas& canvas, const Rect& r, const Rgb& colour)
{
  for (int y = r.Y0; y <= r.Y1; ++y)
  {
    for (int x = r.X0; x <= r.X1; ++x)
    {
      canvas.Blend(x, y, colour, 1.0);
    }
  }
}

double DistanceToSegment(double px, double py, double ax, double ay, double bx, double by)
{
  const double dx = bx - ax, dy = by - ay, lengthSquared = dx * dx + dy * dy;
  double t = lengthSquared > 0 ? ((px - ax) * dx + (py - ay) * dy) / lengthSquared : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (ax + t * dx), py - (ay + t * dy));
}

/// A capsule around the segment, antialiased by coverage; a zero-length segment is a dot. Only
/// pixels inside clip are touched, so values beyond the axes are cut at the plot area's edge.
/// colourAt(x, y) gives each pixel's colour.
template <typename ColourAt>
void DrawSegment(Canvas& canvas, double ax, double ay, double bx, double by, double halfWidth,
  const ColourAt& colourAt, const Rect& clip)
{
  if (!std::isfinite(ax + ay + bx + by))
  {
    return; // an int conversion below would be undefined
  }
  const double reach = halfWidth + 1;
  // Clamped in double first: a value far off the axis must not overflow the int conversion.
  const auto clampX = [&](double v) { return static_cast<int>(std::clamp(v, double(clip.X0), double(clip.X1))); };
  const auto clampY = [&](double v) { return static_cast<int>(std::clamp(v, double(clip.Y0), double(clip.Y1))); };
  const int x0 = clampX(std::floor(std::min(ax, bx) - reach)), x1 = clampX(std::ceil(std::max(ax, bx) + reach));
  const int y0 = clampY(std::floor(std::min(ay, by) - reach)), y1 = clampY(std::ceil(std::max(ay, by) + reach));
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      const double coverage = halfWidth + 0.5 - DistanceToSegment(x, y, ax, ay, bx, by);
      if (coverage > 0)
      {
        canvas.Blend(x, y, colourAt(x, y), coverage);
      }
    }
  }
}

/// A string rendered by FreeType (no render window needed), with its ink box in the image's
/// own coordinates so it can be placed by any corner or centre.
struct TextImage
{
  vtkSmartPointer<vtkImageData> Image;
  int Box[4] = { 0, -1, 0, -1 }; // xmin, xmax, ymin, ymax
  Rgb Colour = Black;
  int Width() const { return this->Box[1] - this->Box[0] + 1; }
  int Height() const { return this->Box[3] - this->Box[2] + 1; }
};

TextImage RenderText(const std::string& text, int sizePx, bool bold = false, bool vertical = false)
{
  TextImage result;
  if (text.empty())
  {
    return result;
  }
  vtkNew<vtkTextProperty> property;
  property->SetFontFamilyToArial();
  property->SetFontSize(sizePx);
  property->SetBold(bold);
  property->SetOrientation(vertical ? 90 : 0);
  // VTK's FreeType tools are one instance with one glyph cache: a cohort's cases write their
  // plots on threads of their own, one string at a time here.
  static std::mutex freeTypeLock;
  const std::lock_guard<std::mutex> lock(freeTypeLock);
  vtkFreeTypeTools* freeType = vtkFreeTypeTools::GetInstance();
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int dpi = 72; // font size in points = pixels
  if (!freeType->RenderString(property, vtkStdString(text), dpi, image) ||
    !freeType->GetBoundingBox(property, vtkStdString(text), dpi, result.Box))
  {
    return TextImage(); // drawn as nothing: a plot without one label beats no plot
  }
  result.Image = image;
  return result;
}

/// Blends the text so that the point (alignX, alignY) of its ink box, in fractions (0: left or
/// bottom, 1: right or top), lands on (x, y).
void DrawText(Canvas& canvas, const TextImage& text, double x, double y, double alignX, double alignY)
{
  if (!text.Image)
  {
    return;
  }
  const int dx = static_cast<int>(std::lround(x - text.Box[0] - alignX * (text.Width() - 1)));
  const int dy = static_cast<int>(std::lround(y - text.Box[2] - alignY * (text.Height() - 1)));
  int extent[6];
  text.Image->GetExtent(extent);
  for (int j = extent[2]; j <= extent[3]; ++j)
  {
    for (int i = extent[0]; i <= extent[1]; ++i)
    {
      const auto* rgba = static_cast<const unsigned char*>(text.Image->GetScalarPointer(i, j, 0));
      canvas.Blend(i + dx, j + dy, text.Colour, rgba[3] / 255.0);
    }
  }
}

std::vector<double> TickValues(double low, double high, double step)
{
  std::vector<double> ticks;
  const double first = std::ceil(low / step - 1e-9) * step;
  for (int i = 0; first + i * step <= high + step * 1e-9 && i < 1000; ++i)
  {
    ticks.push_back(first + i * step);
  }
  return ticks;
}

std::string TickLabel(double value, double step)
{
  const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 12);
  if (std::fabs(value) < step * 1e-6)
  {
    value = 0; // no "-0"
  }
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

std::string BandLegendText(const PlotBand& band)
{
  const std::string range = !std::isfinite(band.FromMm) ? "< " + NumberText(band.ToMm)
    : std::isfinite(band.ToMm)                          ? NumberText(band.FromMm) + "-" + NumberText(band.ToMm)
                                                        : "> " + NumberText(band.FromMm);
  return (band.Label.empty() ? "" : band.Label + " ") + "(" + range + " mm)";
}

/// The x range the times span; an empty or zero span gets 1 s centred on what there is.
std::pair<double, double> TimeRange(const std::vector<double>& timesS)
{
  double low = INFINITY, high = -INFINITY;
  for (double t : timesS)
  {
    if (std::isfinite(t))
    {
      low = std::min(low, t);
      high = std::max(high, t);
    }
  }
  if (!(low <= high))
  {
    return { 0.0, 1.0 };
  }
  if (!(high - low > 0))
  {
    return { low - 0.5, high + 0.5 };
  }
  return { low, high };
}

double AutomaticYMax(const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands, int maxTicks)
{
  double top = 0;
  for (const PlotSeries& s : series)
  {
    for (double v : s.ValuesMm)
    {
      top = std::isfinite(v) ? std::max(top, v) : top;
    }
  }
  for (const PlotBand& b : bands)
  {
    for (double edge : { b.FromMm, b.ToMm })
    {
      top = std::isfinite(edge) ? std::max(top, edge) : top;
    }
  }
  if (!(top > 0))
  {
    return 1;
  }
  top *= 1.05; // headroom: a line at the maximum or a band starting at the top edge stays visible
  const double step = NiceTickStep(top, maxTicks);
  return std::ceil(top / step) * step;
}

struct LegendEntry
{
  TextImage Text;
  Rgb Colour;
  bool IsBand;
  LineStyle Style = LineStyle::Solid;
};

/// Draws a polyline's segment from (ax, ay) to (bx, by) in its style: whole when solid, else
/// only its pattern's "on" stretches; phase: how far along the pattern the segment starts (px),
/// carried from one segment to the next so that the pattern runs on along the line.
template <typename ColourAt>
void DrawStyledSegment(Canvas& canvas, double ax, double ay, double bx, double by, double halfWidth, const ColourAt& colour,
  const Rect& clip, LineStyle style, double& phase)
{
  if (style == LineStyle::Solid)
  {
    DrawSegment(canvas, ax, ay, bx, by, halfWidth, colour, clip);
    return;
  }
  // The pattern along the axis; the round ends add a line width to each "on" stretch.
  const double on = style == LineStyle::Dashed ? 10.0 : 1.0, off = style == LineStyle::Dashed ? 8.0 : 6.0;
  const double length = std::hypot(bx - ax, by - ay);
  double at = 0.0;
  while (at < length)
  {
    const double inPattern = std::fmod(phase + at, on + off);
    const double stretch = inPattern < on ? on - inPattern : on + off - inPattern;
    const double end = std::min(length, at + stretch);
    if (inPattern < on && length > 0.0)
    {
      const double t0 = at / length, t1 = end / length;
      DrawSegment(canvas, ax + t0 * (bx - ax), ay + t0 * (by - ay), ax + t1 * (bx - ax), ay + t1 * (by - ay), halfWidth, colour, clip);
    }
    at = end;
  }
  phase += length;
}

void DrawLegend(Canvas& canvas, const std::vector<LegendEntry>& entries, int left, int top)
{
  int y = top;
  for (const LegendEntry& entry : entries)
  {
    const int rowHeight = std::max(entry.Text.Height(), 12) + GapPx;
    const double middle = y - rowHeight / 2.0;
    if (entry.IsBand)
    {
      const Rect box = { left, static_cast<int>(middle) - 5, left + LegendSwatchPx - 1, static_cast<int>(middle) + 5 };
      FillRect(canvas, box, Frame);
      FillRect(canvas, { box.X0 + 1, box.Y0 + 1, box.X1 - 1, box.Y1 - 1 }, entry.Colour);
    }
    else
    {
      double phase = 0.0;
      DrawStyledSegment(canvas, left, middle, left + LegendSwatchPx - 1, middle, LineHalfWidthPx,
        [&](int, int) { return entry.Colour; }, canvas.Whole(), entry.Style, phase);
    }
    DrawText(canvas, entry.Text, left + LegendSwatchPx + GapPx, middle, 0, 0.5);
    y -= rowHeight;
  }
}

/// On a category axis (cases, not times) each value is its own mark, never joined to the next
/// case's: a dot with a bar across its slot in the series' style, so that a tip (solid), an
/// instrument (dashed) and a margin (dotted) differ there as their lines do elsewhere.
void DrawCategoryMarks(Canvas& canvas, const Canvas& bands, const std::vector<double>& timesS, const PlotSeries& s,
  const DistancePlotFrame& frame, const Rect& clip)
{
  const double slotPx = timesS.size() > 1 ? std::abs(frame.XOf(timesS[1]) - frame.XOf(timesS[0])) : 80.0;
  const double halfBarPx = std::clamp(0.35 * slotPx, PointHalfWidthPx + 2.0, 40.0);
  const auto rim = [&](int x, int y) { return RimColour(bands.At(x, y)); };
  const auto mark = [&](int, int) { return s.Colour; };
  for (const bool outline : { true, false })
  {
    for (std::size_t i = 0; i < timesS.size(); ++i)
    {
      if (!std::isfinite(timesS[i]) || !std::isfinite(s.ValuesMm[i]))
      {
        continue;
      }
      const double x = frame.XOf(timesS[i]), y = frame.YOf(s.ValuesMm[i]);
      double phase = 0.0;
      outline ? DrawStyledSegment(canvas, x - halfBarPx, y, x + halfBarPx, y, LineHalfWidthPx + RimPx, rim, clip, s.Style, phase)
              : DrawStyledSegment(canvas, x - halfBarPx, y, x + halfBarPx, y, LineHalfWidthPx, mark, clip, s.Style, phase);
      outline ? DrawSegment(canvas, x, y, x, y, PointHalfWidthPx + RimPx, rim, clip)
              : DrawSegment(canvas, x, y, x, y, PointHalfWidthPx, mark, clip);
    }
  }
}

/// The series' line, over a rim RimPx wide each side in black or white as the band under it
/// (bands, the picture before any line) asks: readable on every band, and where lines cross.
void DrawSeries(Canvas& canvas, const Canvas& bands, const std::vector<double>& timesS, const PlotSeries& s,
  const DistancePlotFrame& frame, const Rect& clip)
{
  const auto valid = [&](std::size_t i) { return i < timesS.size() && std::isfinite(timesS[i]) && std::isfinite(s.ValuesMm[i]); };
  const auto rim = [&](int x, int y) { return RimColour(bands.At(x, y)); };
  const auto line = [&](int, int) { return s.Colour; };
  for (const bool outline : { true, false })
  {
    double phase = 0.0;
    for (std::size_t i = 0; i < timesS.size(); ++i)
    {
      if (!valid(i))
      {
        continue;
      }
      const double x = frame.XOf(timesS[i]), y = frame.YOf(s.ValuesMm[i]);
      if (valid(i + 1))
      {
        const double bx = frame.XOf(timesS[i + 1]), by = frame.YOf(s.ValuesMm[i + 1]);
        outline ? DrawStyledSegment(canvas, x, y, bx, by, LineHalfWidthPx + RimPx, rim, clip, s.Style, phase)
                : DrawStyledSegment(canvas, x, y, bx, by, LineHalfWidthPx, line, clip, s.Style, phase);
      }
      else if (i == 0 || !valid(i - 1))
      {
        // Alone: no line would show it.
        outline ? DrawSegment(canvas, x, y, x, y, PointHalfWidthPx + RimPx, rim, clip)
                : DrawSegment(canvas, x, y, x, y, PointHalfWidthPx, line, clip);
      }
    }
  }
}

/// The series' note beside its lowest value below zero: under it when there is room in the plot
/// area, else over it, kept inside the area, in black or white as the band there asks.
void DrawDeepestNote(Canvas& canvas, const Canvas& bands, const std::vector<double>& timesS, const PlotSeries& s,
  const DistancePlotFrame& frame, const Rect& plot)
{
  std::size_t deepest = timesS.size();
  for (std::size_t i = 0; i < timesS.size(); ++i)
  {
    if (std::isfinite(timesS[i]) && std::isfinite(s.ValuesMm[i]) && s.ValuesMm[i] < 0 &&
      (deepest == timesS.size() || s.ValuesMm[i] < s.ValuesMm[deepest]))
    {
      deepest = i;
    }
  }
  if (s.DeepestNote.empty() || deepest == timesS.size())
  {
    return;
  }
  TextImage note = RenderText(s.DeepestNote, 12);
  const double y = frame.YOf(s.ValuesMm[deepest]);
  const double half = note.Width() / 2.0;
  const double x = std::max(plot.X0 + half, std::min(frame.XOf(timesS[deepest]), plot.X1 - half));
  const bool under = y - 4 - note.Height() >= plot.Y0;
  const double textY = under ? y - 4 : y + 4; // the text's top when under, its bottom when over
  const double middleY = under ? textY - note.Height() / 2.0 : textY + note.Height() / 2.0;
  note.Colour = RimColour(
    bands.At(static_cast<int>(std::lround(x)), std::clamp(static_cast<int>(std::lround(middleY)), plot.Y0, plot.Y1)));
  DrawText(canvas, note, x, textY, 0.5, under ? 1 : 0);
}

/// Where everything goes. The vertical layout comes first: it depends only on text heights and
/// fixes how many y ticks fit, whose labels then fix the left margin.
struct Layout
{
  DistancePlotFrame Frame;
  Rect Plot;
  double YStep = 1, XStep = 1;
  TextImage Title, XLabel, YLabel;
  std::vector<TextImage> YTickTexts;
  std::vector<LegendEntry> Legend;
  std::vector<std::string> XTickLabels;
};

/// Tick t's label: its number, or on a category axis its name shortened to maxWidthPx.
TextImage XTickText(const Layout& layout, double t, double maxWidthPx)
{
  const auto k = static_cast<long>(std::lround(t)) - 1;
  if (layout.XTickLabels.empty() || k < 0 || k >= static_cast<long>(layout.XTickLabels.size()))
  {
    return RenderText(TickLabel(t, layout.XStep), 12);
  }
  std::string label = layout.XTickLabels[static_cast<std::size_t>(k)];
  TextImage text = RenderText(label, 12);
  while (text.Width() > maxWidthPx && label.size() > 4)
  {
    label = label.substr(0, label.size() - (label.size() > 4 && label.compare(label.size() - 3, 3, "...") == 0 ? 4 : 1)) + "...";
    text = RenderText(label, 12);
  }
  return text;
}

std::vector<LegendEntry> LegendEntries(const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands)
{
  std::vector<LegendEntry> legend;
  for (const PlotSeries& s : series)
  {
    legend.push_back({ RenderText(s.Name, 13), s.Colour, false, s.Style });
  }
  for (const PlotBand& b : bands)
  {
    legend.push_back({ RenderText(BandLegendText(b), 13), b.Colour, true });
  }
  return legend;
}

/// Width and height of the legend drawn whole.
std::array<int, 2> LegendSize(const std::vector<LegendEntry>& legend)
{
  std::array<int, 2> size = { 0, 0 };
  for (const LegendEntry& e : legend)
  {
    size[0] = std::max(size[0], LegendSwatchPx + GapPx + e.Text.Width() + 2 * GapPx);
    size[1] += std::max(e.Text.Height(), 12) + GapPx;
  }
  return size;
}

/// The layout of an image of widthPx x heightPx, the legend's entries already rendered.
Layout LayOut(const std::vector<double>& timesS, const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands,
  const DistancePlotOptions& options, std::vector<LegendEntry> legend, int widthPx, int heightPx)
{
  Layout layout;
  layout.Title = RenderText(options.Title, 18, true);
  layout.XLabel = RenderText(options.XLabel, 14);
  layout.YLabel = RenderText(options.YLabel, 14, false, true);
  DistancePlotFrame& f = layout.Frame;
  const int tickTextHeight = RenderText("0123456789", 12).Height();
  f.BottomPx = TickLengthPx + GapPx + tickTextHeight + GapPx + (layout.XLabel.Image ? layout.XLabel.Height() + GapPx : 0);
  f.TopPx = heightPx - 1 - GapPx - (layout.Title.Image ? layout.Title.Height() + GapPx : GapPx);
  f.TopPx = std::max(f.TopPx, f.BottomPx + 1);
  const int maxYTicks = std::max(2, (f.TopPx - f.BottomPx) / 40);
  f.YMaxMm = options.YMaxMm > 0 ? options.YMaxMm : AutomaticYMax(series, bands, maxYTicks);
  const double lowest = LowestValueMm(series);
  f.YMinMm = options.YMinMm < 0 ? options.YMinMm
    : lowest < 0 && options.YMinStepMm > 0 ? std::floor(lowest / options.YMinStepMm) * options.YMinStepMm
                                          : lowest;
  layout.YStep = NiceTickStep(f.YMaxMm - f.YMinMm, maxYTicks);
  if (options.YMinMm >= 0 && options.YMinStepMm <= 0 && lowest < 0)
  {
    f.YMinMm = std::floor(lowest / layout.YStep - 1e-9) * layout.YStep; // a whole tick below
  }
  int yTickWidth = 0;
  for (double v : TickValues(f.YMinMm, f.YMaxMm, layout.YStep))
  {
    layout.YTickTexts.push_back(RenderText(TickLabel(v, layout.YStep), 12));
    yTickWidth = std::max(yTickWidth, layout.YTickTexts.back().Width());
  }

  layout.Legend = std::move(legend);
  const std::array<int, 2> legendSize = LegendSize(layout.Legend);
  const int legendWidth = std::min(legendSize[0], widthPx * 2 / 5); // long names are cut, not the plot
  f.LegendWhole = legendWidth == legendSize[0] && f.TopPx + 1 >= legendSize[1];
  f.LeftPx = GapPx + (layout.YLabel.Image ? layout.YLabel.Width() + GapPx : 0) + yTickWidth + GapPx + TickLengthPx;
  f.RightPx = std::max(f.LeftPx + 1, widthPx - 1 - GapPx - legendWidth - 2 * GapPx);
  std::tie(f.TimeMinS, f.TimeMaxS) = TimeRange(timesS);
  if (!options.XTickLabels.empty())
  {
    f.TimeMinS = 0.5;
    f.TimeMaxS = static_cast<double>(options.XTickLabels.size()) + 0.5;
  }
  layout.XStep = NiceTickStep(f.TimeMaxS - f.TimeMinS, std::max(2, (f.RightPx - f.LeftPx) / 80));
  if (options.WholeXTicks || !options.XTickLabels.empty())
  {
    layout.XStep = std::max(1.0, layout.XStep); // counts (a cohort's cases) have no halves
  }
  layout.XTickLabels = options.XTickLabels;
  layout.Plot = { f.LeftPx, f.BottomPx, f.RightPx, f.TopPx };
  return layout;
}

void DrawBands(Canvas& canvas, const std::vector<PlotBand>& bands, const DistancePlotFrame& frame, const Rect& plot)
{
  for (const PlotBand& b : bands)
  {
    // The rows whose pixel centres lie inside the band, clipped to the plot area.
    const double low = std::max(frame.YOf(std::min(b.FromMm, b.ToMm)), plot.Y0 - 0.5);
    const double high = std::min(frame.YOf(std::max(b.FromMm, b.ToMm)), plot.Y1 + 0.5);
    if (high > low)
    {
      FillRect(canvas, { plot.X0, static_cast<int>(std::ceil(low - 0.5)), plot.X1, static_cast<int>(std::ceil(high - 0.5)) - 1 }, b.Colour);
    }
  }
}

void DrawAxes(Canvas& canvas, const Layout& layout)
{
  const Rect& p = layout.Plot;
  // The box lies just outside the plot area, so it never hides a value at 0 mm or at the ends.
  FillRect(canvas, { p.X0 - 1, p.Y0 - 1, p.X1 + 1, p.Y0 - 1 }, Frame);
  FillRect(canvas, { p.X0 - 1, p.Y1 + 1, p.X1 + 1, p.Y1 + 1 }, Frame);
  FillRect(canvas, { p.X0 - 1, p.Y0 - 1, p.X0 - 1, p.Y1 + 1 }, Frame);
  FillRect(canvas, { p.X1 + 1, p.Y0 - 1, p.X1 + 1, p.Y1 + 1 }, Frame);
  const std::vector<double> yTicks = TickValues(layout.Frame.YMinMm, layout.Frame.YMaxMm, layout.YStep);
  for (std::size_t i = 0; i < yTicks.size(); ++i)
  {
    const int y = static_cast<int>(std::lround(layout.Frame.YOf(yTicks[i])));
    FillRect(canvas, { p.X0 - 1 - TickLengthPx, y, p.X0 - 2, y }, Frame);
    DrawText(canvas, layout.YTickTexts[i], p.X0 - 1 - TickLengthPx - GapPx / 2, y, 1, 0.5);
  }
  const double first = layout.XTickLabels.empty() ? layout.Frame.TimeMinS : 1.0;
  const double room = layout.Frame.XOf(first + layout.XStep) - layout.Frame.XOf(first) - GapPx;
  for (double t : TickValues(first, layout.Frame.TimeMaxS, layout.XStep))
  {
    const int x = static_cast<int>(std::lround(layout.Frame.XOf(t)));
    FillRect(canvas, { x, p.Y0 - 1 - TickLengthPx, x, p.Y0 - 2 }, Frame);
    DrawText(canvas, XTickText(layout, t, room), x, p.Y0 - 1 - TickLengthPx - GapPx / 2, 0.5, 1);
  }
}

void DrawLabels(Canvas& canvas, const Layout& layout, int heightPx)
{
  const Rect& p = layout.Plot;
  // Centred over the plot area, but shifted right rather than cut at the image's left edge.
  const double titleCentre = std::max((p.X0 + p.X1) / 2.0, GapPx + layout.Title.Width() / 2.0);
  DrawText(canvas, layout.Title, titleCentre, heightPx - 1 - GapPx, 0.5, 1);
  DrawText(canvas, layout.XLabel, (p.X0 + p.X1) / 2.0, GapPx, 0.5, 0);
  DrawText(canvas, layout.YLabel, GapPx, (p.Y0 + p.Y1) / 2.0, 0, 0.5);
  DrawLegend(canvas, layout.Legend, p.X1 + 1 + 2 * GapPx, p.Y1);
}
} // namespace

double LowestValueMm(const std::vector<PlotSeries>& series)
{
  double lowest = 0.0;
  for (const PlotSeries& s : series)
  {
    for (double v : s.ValuesMm)
    {
      lowest = std::isfinite(v) ? std::min(lowest, v) : lowest;
    }
  }
  return lowest;
}

double DistancePlotFrame::XOf(double timeS) const
{
  return this->LeftPx + (timeS - this->TimeMinS) / (this->TimeMaxS - this->TimeMinS) * (this->RightPx - this->LeftPx);
}

double DistancePlotFrame::YOf(double distanceMm) const
{
  return this->BottomPx + (distanceMm - this->YMinMm) / (this->YMaxMm - this->YMinMm) * (this->TopPx - this->BottomPx);
}

double NiceTickStep(double span, int maxTicks)
{
  if (!(span > 0) || !std::isfinite(span))
  {
    return 1;
  }
  const double raw = span / std::max(1, maxTicks);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : { 1.0, 2.0, 5.0 })
  {
    if (m * magnitude >= raw * (1 - 1e-9))
    {
      return m * magnitude;
    }
  }
  return 10 * magnitude;
}

double RelativeLuminance(const Rgb& c)
{
  double l = 0;
  const double weight[3] = { 0.2126, 0.7152, 0.0722 };
  for (int k = 0; k < 3; ++k)
  {
    const double v = c[k] / 255.0;
    l += weight[k] * (v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
  }
  return l;
}

double ContrastRatio(const Rgb& a, const Rgb& b)
{
  const double la = RelativeLuminance(a), lb = RelativeLuminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

vtkSmartPointer<vtkImageData> RenderDistancePlot(const std::vector<double>& timesS,
  const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands,
  const DistancePlotOptions& options, DistancePlotFrame* frame)
{
  if (options.WidthPx <= 0 || options.HeightPx <= 0)
  {
    throw std::invalid_argument("distance plot: the image size must be positive");
  }
  for (const PlotSeries& s : series)
  {
    if (s.ValuesMm.size() != timesS.size())
    {
      throw std::invalid_argument("distance plot: series " + s.Name + " has " + std::to_string(s.ValuesMm.size()) +
        " values for " + std::to_string(timesS.size()) + " times");
    }
  }
  // The legend's entries rendered once: they size the image when it grows to fit them.
  std::vector<LegendEntry> legend = LegendEntries(series, bands);
  int widthPx = options.WidthPx, heightPx = options.HeightPx;
  if (options.GrowToFitLegend)
  {
    const std::array<int, 2> legendSize = LegendSize(legend);
    widthPx = std::max(widthPx, legendSize[0] * 5 / 2 + 1);
    heightPx = std::max(heightPx, legendSize[1] + 40);
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(widthPx, heightPx, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  Canvas canvas(image, widthPx, heightPx);
  FillRect(canvas, canvas.Whole(), White);

  const Layout layout = LayOut(timesS, series, bands, options, std::move(legend), widthPx, heightPx);
  DrawBands(canvas, bands, layout.Frame, layout.Plot);
  if (layout.Frame.YMinMm < 0)
  {
    // The vessel wall: distances above, penetrations below.
    const int zero = static_cast<int>(std::lround(layout.Frame.YOf(0.0)));
    FillRect(canvas, { layout.Plot.X0, zero, layout.Plot.X1, zero }, Frame);
  }
  std::vector<unsigned char> under = canvas.Copy();
  const Canvas bandsOnly(under.data(), widthPx, heightPx);
  for (const PlotSeries& s : series)
  {
    layout.XTickLabels.empty() ? DrawSeries(canvas, bandsOnly, timesS, s, layout.Frame, layout.Plot)
                               : DrawCategoryMarks(canvas, bandsOnly, timesS, s, layout.Frame, layout.Plot);
  }
  for (const PlotSeries& s : series)
  {
    DrawDeepestNote(canvas, bandsOnly, timesS, s, layout.Frame, layout.Plot);
  }
  DrawAxes(canvas, layout);
  DrawLabels(canvas, layout, heightPx);
  if (frame)
  {
    *frame = layout.Frame;
  }
  return image;
}

void WriteDistancePlotPng(const std::string& fileName, const std::vector<double>& timesS,
  const std::vector<PlotSeries>& series, const std::vector<PlotBand>& bands,
  const DistancePlotOptions& options)
{
  WritePngAtomically(RenderDistancePlot(timesS, series, bands, options), fileName);
}
} // namespace vp
