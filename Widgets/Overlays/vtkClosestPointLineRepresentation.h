#ifndef vtkClosestPointLineRepresentation_h
#define vtkClosestPointLineRepresentation_h

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>

class vtkActor;
class vtkCoordinate;
class vtkLineSource;
class vtkRenderer;
class vtkTextActor;

/// A line from the scalpel tip to the closest vessel point, with the vessel and the distance
/// written beside its middle ("portal vein 4.2 mm", "portal vein 1.0 mm inside" for a breach, a
/// z-buffer answer as the interval the truth lies in: "portal vein 1.1-1.9 mm") in white, the
/// line in the class's colour with a dot of fixed screen size at each end, so that it shows at any zoom even when the
/// line itself is a few pixels long. The label is drawn over the scene, never hidden behind a
/// vessel: the number matters most exactly when the tip is among them. Moving it rewrites two
/// points of a two-point line; it hides itself when nothing is in range.
class vtkClosestPointLineRepresentation : public vtkObject
{
public:
  static vtkClosestPointLineRepresentation* New();
  vtkTypeMacro(vtkClosestPointLineRepresentation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Shows the line from tip to point (LPS mm) labelled with the class and the distance (within
  /// boundMm of the truth; 0: exact).
  void SetLine(const double tipMm[3], const double pointMm[3], double distanceMm, bool inside,
    const std::string& className = std::string(), double boundMm = 0.0);
  /// Hides line and label (no class in range).
  void Hide();
  bool IsShown() const;
  /// RGB 0..1 of the line and its dots (default white; the overlays give the nearest class's
  /// readout colour). The label stays white.
  void SetColour(double r, double g, double b);
  /// The label's text, as drawn.
  std::string GetLabelText() const;

  void AddToRenderer(vtkRenderer* renderer);
  void RemoveFromRenderer(vtkRenderer* renderer);

protected:
  vtkClosestPointLineRepresentation();
  ~vtkClosestPointLineRepresentation() override;

  vtkSmartPointer<vtkLineSource> Line;
  vtkSmartPointer<vtkActor> LineActor;
  vtkSmartPointer<vtkTextActor> Label;
  vtkSmartPointer<vtkCoordinate> LabelAnchor; ///< the line's middle, in world coordinates
  vtkSmartPointer<vtkActor> EndsActor;        ///< the two ends as dots of a fixed screen size

private:
  vtkClosestPointLineRepresentation(const vtkClosestPointLineRepresentation&) = delete;
  void operator=(const vtkClosestPointLineRepresentation&) = delete;
};

#endif
