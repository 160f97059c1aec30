#ifndef vtkProximityReadoutRepresentation_h
#define vtkProximityReadoutRepresentation_h

#include "vpDangerLevels.h"
#include "vpProximityResult.h"
#include "vpTrackedFrame.h"
#include "vpTumourProximity.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>
#include <vtkWeakPointer.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

class vtkRenderer;
class vtkTextActor;

/// The numbers a surgeon reads: one line per vessel class in the upper left corner ("portal vein
/// 4.2 mm  warning"), in the class's colour, under a headline with the overall level, and below
/// them, with tumours, the resection margin's line, and, only while it is so, a line saying the
/// frame took longer than its budget. A line is
/// re-typeset only when its text changes (GetNumberOfTextUpdates() counts), so a tool resting
/// still costs nothing.
class vtkProximityReadoutRepresentation : public vtkObject
{
public:
  static vtkProximityReadoutRepresentation* New();
  vtkTypeMacro(vtkProximityReadoutRepresentation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Declares the classes (in the engine's order) with their display colours (RGB 0..1).
  void SetClasses(const std::vector<std::string>& names, const std::vector<std::array<double, 3>>& colours);
  /// The engine that answers ("exact", "zbuffer"; empty: not said), named in the headline
  /// beside the overall level with what its numbers are: exact, or within the frame's error
  /// bound, each class's distance then shown as the interval the truth lies in ("1.1-1.9 mm").
  void SetEngine(const std::string& methodName);
  /// Shows a frame's answers under headline (vp::FrameHeadline: the most severe of the vessels'
  /// level and the margin's, with its cause): per class the tip's distance, inside and level and,
  /// with the whole instrument measured, the instrument's distance ("tool 2.6 mm") or, inside, its
  /// depth and volume ("tool 1.0 mm in, 3.7 mm3") with its own level, so that no level stands
  /// beside a number it does not follow from.
  /// With exact (the exact engine's answer for the same pose, when it was computed beside an
  /// approximate one), each class line gives the exact distance too ("exact 0.2"), and the
  /// headline says that the approximate engine set the level.
  void ShowFrame(const vp::TrackedFrame& frame, const std::string& headline, const vp::ProximityResult* exact = nullptr);
  /// A live stream gave no pose for sinceMs: the headline says TRACKING LOST and each class line
  /// loses its distance ("portal vein      -"), so that the last distance is never read as current.
  /// The next ShowFrame gives them back.
  void ShowTrackingLost(double sinceMs);
  /// The resection margin's line, in the tumours' colour: the tumour that sets the margin's level,
  /// the tip's distance to it and the level ("tumour livertumor01  3.2 mm  VIOLATED  (margin 5
  /// mm)"; inside: "2.1 mm inside  INSIDE"). Null (no tumour): the line is empty.
  void ShowMargin(const vp::TumourMargin* margin, double marginMm);
  /// Shows the last line only for a frame over its budget ("frame 23.4 ms, over the 16.7 ms
  /// budget"); empty otherwise, so a frame in time costs no text update.
  void ShowFrameTime(double frameMs, bool overBudget, double budgetMs);
  /// The text of line i (0: the headline, then one per class, then the margin's, then the
  /// frame-time line).
  std::string GetLineText(int i) const;
  int GetNumberOfLines() const { return static_cast<int>(this->Lines.size()); }
  /// Line i's text actor (where it is drawn, how large).
  vtkTextActor* GetLineActor(int i) const;
  int GetNumberOfTextUpdates() const { return this->TextUpdates; }
  /// Font size in points (default 18).
  void SetFontSize(int points);
  /// The size the lines are drawn at: FontSize, or smaller (down to 8) where the widest line
  /// would not fit the viewport's width at it (a 640 x 480 window; set before each render).
  int GetFittedFontSize() const { return this->FittedFontSize; }

  void AddToRenderer(vtkRenderer* renderer);
  void RemoveFromRenderer(vtkRenderer* renderer);

protected:
  vtkProximityReadoutRepresentation();
  ~vtkProximityReadoutRepresentation() override;

  std::vector<vtkSmartPointer<vtkTextActor>> Lines;
  std::vector<std::string> ClassNames;
  std::vector<vtkRenderer*> Renderers;
  int FontSize = 18;
  int FittedFontSize = 18;
  std::string FittedFor; ///< the texts and width the fitted size was found for
  std::vector<std::pair<vtkWeakPointer<vtkRenderer>, unsigned long>> StartTags; ///< the fitting's observers
  int TextUpdates = 0;
  std::string EngineName;
  bool MarginShown = false;

private:
  vtkProximityReadoutRepresentation(const vtkProximityReadoutRepresentation&) = delete;
  void operator=(const vtkProximityReadoutRepresentation&) = delete;
  void SetLine(int i, const std::string& text);
  void Place();
  /// Shrinks the lines until the widest fits the renderer's width (FittedFontSize), when the
  /// texts or the width changed since the last time.
  void FitToViewport(vtkRenderer* renderer);
  /// The widest line's width in pixels at the fitted size.
  int WidestLinePx(int dpi) const;
  /// Class c's line: the tip's distance and level, and the instrument's with its own.
  std::string ClassLine(const vp::TrackedFrame& frame, std::size_t c, const vp::ProximityResult* exact) const;
};

#endif
