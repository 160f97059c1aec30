#include "vtkDistancePlotRepresentation.h"

#include "vpDangerBands.h"
#include "vpDistancePlot.h"

#include <vtkActor2D.h>
#include <vtkCoordinate.h>
#include <vtkImageData.h>
#include <vtkImageMapper.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderer.h>

#include <limits>

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

vtkDistancePlotRepresentation::~vtkDistancePlotRepresentation() = default;

void vtkDistancePlotRepresentation::SetClasses(const std::vector<std::string>& names)
{
  this->ClassNames = names;
  this->ClearHistory();
}

void vtkDistancePlotRepresentation::SetDangerThresholds(const vp::DangerThresholds& thresholds)
{
  this->Thresholds = thresholds;
  this->Redraw();
}

void vtkDistancePlotRepresentation::SetSizePx(int width, int height)
{
  this->WidthPx = width;
  this->HeightPx = height;
  this->Actor->GetPositionCoordinate()->SetValue(-width - 10, 10);
  this->Redraw();
}

void vtkDistancePlotRepresentation::ClearHistory()
{
  this->Times.clear();
  this->ValuesMm.assign(this->ClassNames.size(), {});
  this->Redraw();
}

void vtkDistancePlotRepresentation::AddFrame(double timeS, const vp::ProximityResult& proximity)
{
  this->Times.push_back(timeS);
  for (std::size_t c = 0; c < this->ClassNames.size(); ++c)
  {
    const bool known = c < proximity.Classes.size() && proximity.Classes[c].InRange;
    this->ValuesMm[c].push_back(known ? proximity.Classes[c].DistanceMm : std::numeric_limits<double>::quiet_NaN());
  }
  while (!this->Times.empty() && this->Times.front() < timeS - this->TimeWindowS)
  {
    this->Times.pop_front();
    for (auto& values : this->ValuesMm)
    {
      values.pop_front();
    }
  }
  this->Redraw();
}

void vtkDistancePlotRepresentation::Redraw()
{
  std::vector<vp::PlotSeries> series(this->ClassNames.size());
  for (std::size_t c = 0; c < series.size(); ++c)
  {
    series[c].Name = this->ClassNames[c];
    series[c].Colour = vp::PlotSeriesColour(this->ClassNames[c], static_cast<int>(c));
    series[c].ValuesMm.assign(this->ValuesMm[c].begin(), this->ValuesMm[c].end());
  }
  vp::DistancePlotOptions options;
  options.WidthPx = this->WidthPx;
  options.HeightPx = this->HeightPx;
  options.Title = "tip distance (mm)";
  options.YLabel = "";
  // A fixed scale: a plot that rescales with every frame is hard to read at a glance.
  options.YMaxMm = std::max(this->Thresholds.CautionMm * 2.0, 20.0);
  const std::vector<double> times(this->Times.begin(), this->Times.end());
  this->Mapper->SetInputData(
    vp::RenderDistancePlot(times, series, vp::DangerBands(this->Thresholds, options.YMaxMm), options));
  ++this->Redraws;
  this->Modified();
}

vtkImageData* vtkDistancePlotRepresentation::GetImage() const
{
  return vtkImageData::SafeDownCast(this->Mapper->GetInput());
}

void vtkDistancePlotRepresentation::AddToRenderer(vtkRenderer* renderer)
{
  renderer->AddActor2D(this->Actor);
}

void vtkDistancePlotRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  renderer->RemoveActor2D(this->Actor);
}

void vtkDistancePlotRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TimeWindowS: " << this->TimeWindowS << "\n" << indent << "SizePx: " << this->WidthPx << " x "
     << this->HeightPx << "\n" << indent << "Samples: " << this->Times.size() << "\n" << indent
     << "NumberOfRedraws: " << this->Redraws << "\n";
}
