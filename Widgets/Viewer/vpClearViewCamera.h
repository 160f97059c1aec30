#ifndef vpClearViewCamera_h
#define vpClearViewCamera_h

class vtkRenderer;

namespace vp
{
/// Whether a world point is in plain sight in the renderer's last rendered picture: inside the
/// viewport, and nothing in the depth buffer there more than toleranceMm in front of it (the
/// instrument's own tip face, a surface the point lies on, are within that).
bool PointInPlainSight(vtkRenderer* renderer, const double point[3], double toleranceMm = 3.0);

/// Places the renderer's camera so that the scalpel's tip and (when given) the closest vessel
/// point are both in plain sight: beside the tool, looking across the line from the tip to the
/// closest point, turned about the tool's axis in 30 degree steps and tilted (toward the outside
/// of the wall at the closest point first, then level, then toward either end of the tool) until a
/// rendered picture's depth buffer shows both (the first such), the tool's shaft up the screen. A
/// tip tipDepthMm inside its vessel counts as in sight behind that much of the wall. Renders each
/// candidate. Returns false when none shows both (the last one tried is kept).
bool PlaceClearViewCamera(
  vtkRenderer* renderer, const double tip[3], const double axis[3], const double* closest, double tipDepthMm = 0.0);
} // namespace vp

#endif
