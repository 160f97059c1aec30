#include "vtkDistancePlotRepresentation.h"

#include "vpPlotValues.h"

#include "vpDangerBands.h"
#include "vpDistancePlot.h"

#include <vtkActor2D.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkCoordinate.h>
#include <vtkImageData.h>
#include <vtkImageMapper.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderer.h>

#include <algorithm>

vtkStandardNewMacro(vtkDistancePlotRepresentation);

vtkDistancePlotRepresentation::vtkDistancePlotRepresentation()
  : Mapper(vtkSmartPointer<vtkImageMapper>::New())
  , Actor(vtkSmartPointer<vtkActor2D>::New())
{
  // The plot's bytes are shown as they are: window 255 at level 127.5 maps 0..255 to itself.
  this->Mapper->SetColorWindow(255.0);
  this->Mapper->SetColorLevel(127.5);
  this->Actor->SetMapper(this->Mapper);
  // Anchored to the lower right corner: a pixel offset from a normalised reference point.
  vtkNew<vtkCoordinate> corner;
  corner->SetCoordinateSystemToNormalizedViewport();
  corner->SetValue(1.0, 0.0);
  this->Actor->GetPositionCoordinate()->SetReferenceCoordinate(corner);
  this->Actor->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  this->SetSizePx(480, 240);
}

vtkDistancePlotRepresentation::~vtkDistancePlotRepresentation()
{
  if (this->Renderer) // null once the renderer is gone
  {
    this->RemoveFromRenderer(this->Renderer);
  }
}

void vtkDistancePlotRepresentation::Invalidate()
{
  this->Stale = true;
  this->Modified();
}

void vtkDistancePlotRepresentation::RedrawIfStale()
{
  if (this->Stale)
  {
    this->Redraw();
  }
}

void vtkDistancePlotRepresentation::SetClasses(const std::vector<std::string>& names)
{
  this->ClassNames = names;
  this->ClearHistory();
}

void vtkDistancePlotRepresentation::SetDangerThresholds(const vp::DangerThresholds& thresholds)
{
  this->Thresholds = thresholds;
  this->Invalidate();
}

void vtkDistancePlotRepresentation::SetSizePx(int width, int height)
{
  this->WidthPx = width;
  this->HeightPx = height;
  this->Actor->GetPositionCoordinate()->SetValue(-width - 10, 10);
  this->Invalidate();
}

void vtkDistancePlotRepresentation::ClearHistory()
{
  this->Times.clear();
  this->ValuesMm.assign(this->ClassNames.size(), {});
  this->InstrumentValuesMm.assign(this->ClassNames.size(), {});
  this->VolumesMm3.assign(this->ClassNames.size(), {});
  this->ShowsInstrument = false;
  this->Invalidate();
}

void vtkDistancePlotRepresentation::AddFrame(const vp::TrackedFrame& frame)
{
  this->Times.push_back(frame.TimeS);
  this->ShowsInstrument = this->ShowsInstrument || !frame.Surface.empty();
  for (std::size_t c = 0; c < this->ClassNames.size(); ++c)
  {
    this->ValuesMm[c].push_back(vp::TipPlotValueMm(frame, c));
    this->InstrumentValuesMm[c].push_back(vp::InstrumentPlotValueMm(frame, c));
    this->VolumesMm3[c].push_back(vp::InstrumentVolumeMm3(frame, c));
  }
  while (!this->Times.empty() && this->Times.front() < frame.TimeS - this->TimeWindowS)
  {
    this->Times.pop_front();
    for (auto* history : { &this->ValuesMm, &this->InstrumentValuesMm, &this->VolumesMm3 })
    {
      for (auto& values : *history)
      {
        values.pop_front();
      }
    }
  }
  this->Invalidate();
}

void vtkDistancePlotRepresentation::Redraw()
{
  std::vector<vp::PlotSeries> series;
  for (std::size_t c = 0; c < this->ClassNames.size(); ++c)
  {
    const vp::Rgb colour = vp::ClassDisplayColour(this->ClassNames[c], static_cast<int>(c));
    series.push_back({ this->ClassNames[c], colour, { this->ValuesMm[c].begin(), this->ValuesMm[c].end() } });
    if (this->ShowsInstrument)
    {
      const auto& volumes = this->VolumesMm3[c];
      const double largest = volumes.empty() ? 0.0 : *std::max_element(volumes.begin(), volumes.end());
      series.push_back({ this->ClassNames[c] + " (instrument)", vp::InstrumentColour(colour),
        { this->InstrumentValuesMm[c].begin(), this->InstrumentValuesMm[c].end() }, vp::InstrumentVolumeNote(largest),
        vp::LineStyle::Dashed });
    }
  }
  const std::vector<vp::PlotBand> bands = vp::DangerBands(this->Thresholds, vp::LowestValueMm(series) < 0);
  vp::DistancePlotOptions options;
  options.WidthPx = this->WidthPx;
  options.HeightPx = this->HeightPx;
  // Never smaller than its legend needs: a window of 1000 x 700 cut it off.
  options.GrowToFitLegend = true;
  options.Title = this->ShowsInstrument ? "tip and instrument distance (mm)" : "tip distance (mm)";
  options.YLabel = "";
  // A fixed scale: a plot that rescales with every frame is hard to read at a glance.
  options.YMaxMm = std::max(this->Thresholds.CautionMm * 2.0, 20.0);
  const std::vector<double> times(this->Times.begin(), this->Times.end());
  // Fixed below zero too: 5 mm under the wall, deeper in 5 mm steps only when something goes deeper.
  options.YMinStepMm = 5.0;
  vtkSmartPointer<vtkImageData> image = vp::RenderDistancePlot(times, series, bands, options, &this->Frame);
  // Placed by the width it has: grown to its legend, it would otherwise run off the window's edge
  // ("portal_vein (instrume" in every 1280 x 800 screenshot).
  this->Actor->GetPositionCoordinate()->SetValue(-image->GetDimensions()[0] - 10, 10);
  this->Mapper->SetInputData(image);
  ++this->Redraws;
  this->Stale = false;
}

const vp::DistancePlotFrame& vtkDistancePlotRepresentation::GetFrame()
{
  this->RedrawIfStale();
  return this->Frame;
}

vtkImageData* vtkDistancePlotRepresentation::GetImage()
{
  this->RedrawIfStale();
  return vtkImageData::SafeDownCast(this->Mapper->GetInput());
}

vtkActor2D* vtkDistancePlotRepresentation::GetActor() const
{
  return this->Actor;
}

void vtkDistancePlotRepresentation::AddToRenderer(vtkRenderer* renderer)
{
  if (this->Renderer && this->Renderer != renderer)
  {
    this->RemoveFromRenderer(this->Renderer);
  }
  renderer->AddActor2D(this->Actor);
  if (this->Renderer != renderer)
  {
    vtkNew<vtkCallbackCommand> draw;
    draw->SetClientData(this);
    draw->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
      static_cast<vtkDistancePlotRepresentation*>(self)->RedrawIfStale();
    });
    this->StartTag = renderer->AddObserver(vtkCommand::StartEvent, draw);
    this->Renderer = renderer;
  }
}

void vtkDistancePlotRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  renderer->RemoveActor2D(this->Actor);
  if (renderer == this->Renderer)
  {
    renderer->RemoveObserver(this->StartTag);
    this->Renderer = nullptr;
  }
}

void vtkDistancePlotRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TimeWindowS: " << this->TimeWindowS << "\n" << indent << "SizePx: " << this->WidthPx << " x "
     << this->HeightPx << "\n" << indent << "Samples: " << this->Times.size() << "\n" << indent
     << "NumberOfRedraws: " << this->Redraws << "\n";
}
