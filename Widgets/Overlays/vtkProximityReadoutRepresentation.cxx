#include "vtkProximityReadoutRepresentation.h"

#include "vpClassName.h"

#include "vpDangerBands.h"
#include "vpFrameHeadline.h"
#include "vpPlotValues.h"

#include <vtkCallbackCommand.h>
#include <vtkCoordinate.h>
#include <vtkTextRenderer.h>
#include <vtkWindow.h>
#include <cmath>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>

vtkStandardNewMacro(vtkProximityReadoutRepresentation);

namespace
{
std::string Upper(std::string text)
{
  for (char& c : text)
  {
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return text;
}
} // namespace

vtkProximityReadoutRepresentation::vtkProximityReadoutRepresentation()
{
  this->SetClasses({}, {});
}

vtkProximityReadoutRepresentation::~vtkProximityReadoutRepresentation()
{
  for (const auto& [renderer, tag] : this->StartTags)
  {
    if (renderer) // null once the renderer is gone
    {
      renderer->RemoveObserver(tag);
    }
  }
}

void vtkProximityReadoutRepresentation::SetClasses(
  const std::vector<std::string>& names, const std::vector<std::array<double, 3>>& colours)
{
  for (vtkRenderer* r : this->Renderers)
  {
    for (auto& line : this->Lines)
    {
      r->RemoveActor2D(line);
    }
  }
  this->ClassNames = names;
  this->Lines.clear();
  for (std::size_t i = 0; i <= names.size() + 2; ++i)
  {
    const bool marginLine = i == names.size() + 1;
    const bool frameTimeLine = i == names.size() + 2;
    auto line = vtkSmartPointer<vtkTextActor>::New();
    vtkTextProperty* text = line->GetTextProperty();
    text->SetFontFamilyToCourier(); // columns line up
    text->SetBold(i == 0);
    text->SetShadow(true);
    // A dark backing like the view's background: the colours below keep their contrast where the
    // text passes over a white shaft or a bright vessel.
    text->SetBackgroundColor(0.08, 0.09, 0.12);
    text->SetBackgroundOpacity(0.7);
    // Class colours are for surfaces; lifted towards white until they read on the view's background
    // (WCAG contrast 4.5), the same hue as the class's model and plot line.
    const std::array<double, 3> c = i == 0 || i - 1 >= colours.size() ? std::array<double, 3>{ 1, 1, 1 } : colours[i - 1];
    text->SetColor(vp::ToFraction(vp::ReadoutTextColour(vp::ToRgb(c))).data());
    if (frameTimeLine)
    {
      text->SetColor(1.0, 0.65, 0.2); // amber: a late answer, not a vessel
    }
    if (marginLine)
    {
      text->SetColor(vp::ToFraction(vp::ReadoutTextColour(vp::TumourDisplayColour)).data());
    }
    line->SetInput(i == 0 ? "no pose yet" : frameTimeLine || marginLine ? "" : (vp::ReadableClassName(names[i - 1]) + ": -").c_str());
    this->Lines.push_back(line);
    for (vtkRenderer* r : this->Renderers)
    {
      r->AddActor2D(line);
    }
  }
  this->Place();
  this->Modified();
}

void vtkProximityReadoutRepresentation::SetFontSize(int points)
{
  this->FontSize = points;
  this->FittedFontSize = points;
  this->FittedFor.clear();
  this->Place();
  this->Modified();
}

int vtkProximityReadoutRepresentation::WidestLinePx(int dpi) const
{
  vtkTextRenderer* text = vtkTextRenderer::GetInstance();
  int widest = 0;
  for (const auto& line : this->Lines)
  {
    int box[4] = { 0, 0, 0, 0 };
    const char* input = line->GetInput();
    if (text && input && *input && text->GetBoundingBox(line->GetTextProperty(), std::string(input), box, dpi))
    {
      widest = std::max(widest, box[1] - box[0] + 1);
    }
  }
  return widest;
}

void vtkProximityReadoutRepresentation::FitToViewport(vtkRenderer* renderer)
{
  const int width = renderer->GetSize()[0];
  std::string key = std::to_string(width);
  for (const auto& line : this->Lines)
  {
    key += '\n' + std::string(line->GetInput() ? line->GetInput() : "");
  }
  if (width <= 0 || key == this->FittedFor)
  {
    return;
  }
  this->FittedFor = key;
  const int dpi = renderer->GetVTKWindow() ? renderer->GetVTKWindow()->GetDPI() : 72;
  const int available = width - 12 - 8; // the lines start 12 pixels in
  // The font is monospaced: the width scales with the size, so one guess and a check or two.
  this->FittedFontSize = this->FontSize;
  this->Place();
  const int widest = this->WidestLinePx(dpi);
  if (widest > available)
  {
    this->FittedFontSize = std::max(8, this->FontSize * available / std::max(1, widest));
    this->Place();
    while (this->FittedFontSize > 8 && this->WidestLinePx(dpi) > available)
    {
      --this->FittedFontSize;
      this->Place();
    }
  }
}

void vtkProximityReadoutRepresentation::Place()
{
  // Each line sits a fixed number of pixels below the viewport's top left corner, whatever the
  // window size: a display-pixel offset from a normalised-viewport reference point.
  const int size = this->FittedFontSize;
  int downPx = 10 + size + 4;
  for (std::size_t i = 0; i < this->Lines.size(); ++i)
  {
    vtkTextActor* line = this->Lines[i];
    line->GetTextProperty()->SetFontSize(i == 0 ? size + 4 : size);
    line->GetTextProperty()->SetJustificationToLeft();
    line->GetTextProperty()->SetVerticalJustificationToBottom();
    vtkNew<vtkCoordinate> corner;
    corner->SetCoordinateSystemToNormalizedViewport();
    corner->SetValue(0.0, 1.0);
    line->GetPositionCoordinate()->SetReferenceCoordinate(corner);
    line->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    line->GetPositionCoordinate()->SetValue(12, -downPx);
    downPx += (i == 0 ? 12 : 6) + size;
  }
}

void vtkProximityReadoutRepresentation::SetLine(int i, const std::string& text)
{
  const char* current = this->Lines[i]->GetInput();
  if (!current || text != current)
  {
    this->Lines[i]->SetInput(text.c_str());
    ++this->TextUpdates;
  }
}

void vtkProximityReadoutRepresentation::SetEngine(const std::string& methodName)
{
  this->EngineName = methodName;
  this->Modified();
}

void vtkProximityReadoutRepresentation::ShowFrame(
  const vp::TrackedFrame& frame, const std::string& headline, const vp::ProximityResult* exact)
{
  // Three engines' numbers read alike unless the screen says whose they are and how sure.
  const vp::ProximityResult& proximity = frame.Proximity;
  const double bound = proximity.ErrorBoundMm;
  const std::string engine = this->EngineName == "zbuffer" ? "z-buffer" : this->EngineName;
  char headlineText[192];
  std::snprintf(headlineText, sizeof(headlineText), bound > 0 ? "%-8s | %s engine%s, within %.2f mm" : "%-8s | %s engine%s",
    headline.c_str(), engine.c_str(), exact ? " sets the level" : "", bound);
  this->SetLine(0, this->EngineName.empty() ? headline : std::string(headlineText));
  for (std::size_t c = 0; c < this->ClassNames.size() && c < proximity.Classes.size(); ++c)
  {
    this->SetLine(static_cast<int>(c) + 1, this->ClassLine(frame, c, exact));
  }
}

std::string vtkProximityReadoutRepresentation::ClassLine(
  const vp::TrackedFrame& frame, std::size_t c, const vp::ProximityResult* exact) const
{
  const vp::ClassProximity& p = frame.Proximity.Classes[c];
  const double bound = frame.Proximity.ErrorBoundMm;
  char text[160];
  const std::string name = vp::ReadableClassName(this->ClassNames[c]);
  if (!p.InRange)
  {
    std::snprintf(text, sizeof(text), "%-15s    out of range", name.c_str());
  }
  else
  {
    const bool inside = p.Inside && *p.Inside;
    std::snprintf(text, sizeof(text), "%-15s %9s mm%s  %s", name.c_str(), vp::DistanceText(p.DistanceMm, bound).c_str(),
      inside ? " inside" : "", c < frame.ClassLevels.size() ? vp::DangerLevelName(frame.ClassLevels[c]) : "");
    if (exact && c < exact->Classes.size() && exact->Classes[c].InRange)
    {
      const vp::ClassProximity& e = exact->Classes[c];
      char exactText[64];
      std::snprintf(exactText, sizeof(exactText), "  (exact %.1f%s)", e.DistanceMm, e.Inside && *e.Inside ? " inside" : "");
      std::strncat(text, exactText, sizeof(text) - std::strlen(text) - 1);
    }
  }
  std::string line = text;
  const char* level = c < frame.InstrumentClassLevels.size() ? vp::DangerLevelName(frame.InstrumentClassLevels[c]) : "";
  const auto& penetrations = frame.Penetrations;
  // Inside as the level takes it (any depth or volume); a volume that rounds to nothing is not
  // printed beside a depth ("1.3 mm in, 0.0 mm^3" read as a contradiction).
  if (c < penetrations.size() && penetrations[c].Known && (penetrations[c].VolumeMm3 > 0.0 || penetrations[c].DepthMm > 0.0))
  {
    if (penetrations[c].VolumeMm3 >= 0.05)
    {
      std::snprintf(text, sizeof(text), "  | tool %.1f mm in, %.1f mm^3  %s", penetrations[c].DepthMm, penetrations[c].VolumeMm3, level);
    }
    else
    {
      std::snprintf(text, sizeof(text), "  | tool %.1f mm in  %s", penetrations[c].DepthMm, level);
    }
    line += text;
  }
  else if (c < frame.Surface.size() && frame.Surface[c].InRange)
  {
    std::snprintf(text, sizeof(text), "  | tool %.1f mm  %s", frame.Surface[c].DistanceMm, level);
    line += text;
  }
  return line;
}

void vtkProximityReadoutRepresentation::ShowMargin(const vp::TumourMargin* margin, double marginMm)
{
  const int line = static_cast<int>(this->Lines.size()) - 2;
  this->MarginShown = margin && margin->Worst >= 0;
  if (!this->MarginShown)
  {
    this->SetLine(line, "");
    return;
  }
  const vp::TumourProximity& t = margin->Tumours[static_cast<std::size_t>(margin->Worst)];
  char text[160];
  std::snprintf(text, sizeof(text), "%-15s %6.1f mm%s  %s  (margin %g mm)", vp::TumourSpoken(t.Id).c_str(), std::abs(t.SignedMm),
    t.SignedMm < 0.0 ? " inside" : "", Upper(vp::MarginLevelName(margin->Level)).c_str(), marginMm);
  this->SetLine(line, text);
}

void vtkProximityReadoutRepresentation::ShowTrackingLost(double sinceMs)
{
  char text[96];
  std::snprintf(text, sizeof(text), "TRACKING LOST (no pose for %.0f ms)", sinceMs);
  this->SetLine(0, text);
  for (std::size_t c = 0; c < this->ClassNames.size(); ++c)
  {
    std::snprintf(text, sizeof(text), "%-15s      -", vp::ReadableClassName(this->ClassNames[c]).c_str());
    this->SetLine(static_cast<int>(c) + 1, text);
  }
  if (this->MarginShown)
  {
    this->SetLine(static_cast<int>(this->Lines.size()) - 2, "tumour                -");
  }
}

void vtkProximityReadoutRepresentation::ShowFrameTime(double frameMs, bool overBudget, double budgetMs)
{
  char text[96] = "";
  if (overBudget)
  {
    std::snprintf(text, sizeof(text), "frame %.1f ms, over the %.1f ms budget", frameMs, budgetMs);
  }
  this->SetLine(static_cast<int>(this->Lines.size()) - 1, text);
}

vtkTextActor* vtkProximityReadoutRepresentation::GetLineActor(int i) const
{
  return this->Lines[static_cast<std::size_t>(i)];
}

std::string vtkProximityReadoutRepresentation::GetLineText(int i) const
{
  const char* text = this->Lines[i]->GetInput();
  return text ? text : "";
}

void vtkProximityReadoutRepresentation::AddToRenderer(vtkRenderer* renderer)
{
  this->Renderers.push_back(renderer);
  for (auto& line : this->Lines)
  {
    renderer->AddActor2D(line);
  }
  vtkNew<vtkCallbackCommand> fit;
  fit->SetClientData(this);
  fit->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
    static_cast<vtkProximityReadoutRepresentation*>(self)->FitToViewport(static_cast<vtkRenderer*>(caller));
  });
  this->StartTags.emplace_back(renderer, renderer->AddObserver(vtkCommand::StartEvent, fit));
}

void vtkProximityReadoutRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  for (auto& line : this->Lines)
  {
    renderer->RemoveActor2D(line);
  }
  for (auto it = this->StartTags.begin(); it != this->StartTags.end();)
  {
    if (it->first == renderer)
    {
      renderer->RemoveObserver(it->second);
      it = this->StartTags.erase(it);
    }
    else
    {
      ++it;
    }
  }
  this->Renderers.erase(std::remove(this->Renderers.begin(), this->Renderers.end(), renderer), this->Renderers.end());
}

void vtkProximityReadoutRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (int i = 0; i < this->GetNumberOfLines(); ++i)
  {
    os << indent << "Line " << i << ": " << this->GetLineText(i) << "\n";
  }
  os << indent << "FontSize: " << this->FontSize << "\n" << indent << "NumberOfTextUpdates: " << this->TextUpdates << "\n";
}
