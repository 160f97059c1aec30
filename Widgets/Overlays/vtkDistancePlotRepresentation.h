#ifndef vtkDistancePlotRepresentation_h
#define vtkDistancePlotRepresentation_h

#include "vpDangerLevels.h"
#include "vpDistancePlot.h"
#include "vpProximityResult.h"
#include "vtkScalpelTrackingLogic.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>
#include <vtkWeakPointer.h>

#include <deque>
#include <string>
#include <vector>

class vtkActor2D;
class vtkImageData;
class vtkImageMapper;
class vtkRenderer;

/// The distance-over-time plot in the lower right corner of the view: the tip's distance to each
/// vessel class over the last TimeWindowS seconds, and the whole instrument's when it is
/// measured, on the danger bands; inside a vessel below zero (vp::TipPlotValueMm and
/// vp::InstrumentPlotValueMm), the instrument's largest penetration volume in the window written
/// at its deepest point (vp::InstrumentVolumeNote). Drawn by the same rasteriser and with the same values as the
/// report's distance.png, so the two look alike.
/// Redrawn when the renderer it is in starts a render after a frame was added (or the settings
/// changed), never when only the camera moves, and never for frames no render shows: a replay
/// that renders a few key frames of many draws the plot a few times (the demo's screenshots
/// drew it 918 times for 9 pictures).
class vtkDistancePlotRepresentation : public vtkObject
{
public:
  static vtkDistancePlotRepresentation* New();
  vtkTypeMacro(vtkDistancePlotRepresentation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetClasses(const std::vector<std::string>& names);
  void SetDangerThresholds(const vp::DangerThresholds& thresholds);
  /// Seconds of history shown (default 20).
  vtkSetClampMacro(TimeWindowS, double, 0.1, 1e6);
  vtkGetMacro(TimeWindowS, double);
  /// Plot size in pixels (default 480 x 240).
  void SetSizePx(int width, int height);

  /// Appends a frame's distances (out-of-range classes leave a gap); the plot is drawn again
  /// before the next render.
  void AddFrame(const vp::TrackedFrame& frame);
  void ClearHistory();
  int GetNumberOfSamples() const { return static_cast<int>(this->Times.size()); }
  int GetNumberOfRedraws() const { return this->Redraws; }
  /// The plot as it stands now (drawn first when a frame came since the last drawing), and where
  /// its parts went (its legend whole or not). The image is never smaller than its legend needs.
  vtkImageData* GetImage();
  const vp::DistancePlotFrame& GetFrame();

  void AddToRenderer(vtkRenderer* renderer);
  void RemoveFromRenderer(vtkRenderer* renderer);
  /// The image's actor, placed by its lower right corner 10 pixels in from the viewport's.
  vtkActor2D* GetActor() const;

protected:
  vtkDistancePlotRepresentation();
  ~vtkDistancePlotRepresentation() override;

  std::vector<std::string> ClassNames;
  std::deque<double> Times;
  std::vector<std::deque<double>> ValuesMm;           ///< per class, the tip
  std::vector<std::deque<double>> InstrumentValuesMm; ///< per class, the whole instrument
  std::vector<std::deque<double>> VolumesMm3;         ///< per class, the instrument's penetration volume
  bool ShowsInstrument = false; ///< a frame in the window carried the whole instrument
  vp::DangerThresholds Thresholds;
  double TimeWindowS = 20.0;
  int WidthPx = 480;
  int HeightPx = 240;
  int Redraws = 0;
  vp::DistancePlotFrame Frame;
  bool Stale = true; ///< something changed since the plot was last drawn
  vtkSmartPointer<vtkImageMapper> Mapper;
  vtkSmartPointer<vtkActor2D> Actor;
  vtkWeakPointer<vtkRenderer> Renderer; ///< the renderer whose StartEvent draws a stale plot
  unsigned long StartTag = 0;

private:
  vtkDistancePlotRepresentation(const vtkDistancePlotRepresentation&) = delete;
  void operator=(const vtkDistancePlotRepresentation&) = delete;
  void Redraw();
  /// Marks the plot for drawing before the next render.
  void Invalidate();
  void RedrawIfStale();
};

#endif
