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

/// A line from the scalpel tip to the closest vessel point, with the distance written beside its
/// middle ("4.2 mm", or "1.0 mm inside" for a breach). The label is drawn over the scene, never
/// hidden behind a vessel: the number matters most exactly when the tip is among them.
/// Moving it rewrites two points of a two-point line; it hides itself when nothing is in range.
class vtkClosestPointLineRepresentation : public vtkObject
{
public:
  static vtkClosestPointLineRepresentation* New();
  vtkTypeMacro(vtkClosestPointLineRepresentation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Shows the line from tip to point (LPS mm) labelled with the distance.
  void SetLine(const double tipMm[3], const double pointMm[3], double distanceMm, bool inside);
  /// Hides line and label (no class in range).
  void Hide();
  bool IsShown() const;
  /// RGB 0..1 of line and label (default yellow, readable on the dark view and the vessels).
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

private:
  vtkClosestPointLineRepresentation(const vtkClosestPointLineRepresentation&) = delete;
  void operator=(const vtkClosestPointLineRepresentation&) = delete;
};

#endif
