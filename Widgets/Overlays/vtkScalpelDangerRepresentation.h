#ifndef vtkScalpelDangerRepresentation_h
#define vtkScalpelDangerRepresentation_h

#include "vpDangerLevels.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>

class vtkActor;
class vtkMatrix4x4;
class vtkPolyData;
class vtkRenderer;

/// The scalpel, drawn where it is and coloured by danger level.
///
/// A pose only changes the actor's user matrix: the surface is never copied or transformed, so
/// a moving tool costs the GPU a uniform, not a re-upload. The colour changes only when the
/// level does (GetNumberOfColourChanges() counts them). Default colours are the paper's white ->
/// light gray -> dark gray, then yellow for danger and magenta for a breach, hues no vessel class
/// has (vp::DangerLevelColour).
class vtkScalpelDangerRepresentation : public vtkObject
{
public:
  static vtkScalpelDangerRepresentation* New();
  vtkTypeMacro(vtkScalpelDangerRepresentation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The instrument surface in model coordinates.
  void SetScalpelSurface(vtkPolyData* surface);
  /// Model-to-world, row-major (as vtkScalpelModel holds it).
  void SetModelToWorld(const std::array<double, 16>& matrix);

  void SetDangerLevel(vp::DangerLevel level);
  vp::DangerLevel GetDangerLevel() const { return this->Level; }
  /// RGB 0..255 of a level; takes effect at once when it is the current level.
  void SetLevelColour(vp::DangerLevel level, const std::array<unsigned char, 3>& rgb);
  std::array<unsigned char, 3> GetLevelColour(vp::DangerLevel level) const;
  int GetNumberOfColourChanges() const { return this->ColourChanges; }

  vtkActor* GetActor() const { return this->Actor; }
  void AddToRenderer(vtkRenderer* renderer);
  void RemoveFromRenderer(vtkRenderer* renderer);

protected:
  vtkScalpelDangerRepresentation();
  ~vtkScalpelDangerRepresentation() override;

  vtkSmartPointer<vtkActor> Actor;
  vtkSmartPointer<vtkMatrix4x4> Pose;
  std::array<std::array<unsigned char, 3>, vp::NumberOfDangerLevels> Colours;
  vp::DangerLevel Level = vp::DangerLevel::Safe;
  int ColourChanges = 0;

private:
  vtkScalpelDangerRepresentation(const vtkScalpelDangerRepresentation&) = delete;
  void operator=(const vtkScalpelDangerRepresentation&) = delete;
  void ApplyColour();
};

#endif
