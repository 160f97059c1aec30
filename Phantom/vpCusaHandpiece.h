#ifndef vpCusaHandpiece_h
#define vpCusaHandpiece_h

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace vp
{
/// Dimensions of the default scalpel, a CUSA-like ultrasonic aspirator handpiece (mm).
struct CusaHandpieceDimensions
{
  static constexpr double TipRadiusMm = 1.4;      ///< the tip tube: 2.8 mm diameter
  static constexpr double TipLengthMm = 38.0;     ///< from the tip to the start of the taper
  static constexpr double TaperLengthMm = 20.0;   ///< the conical nose, tube to body
  static constexpr double BodyRadiusMm = 9.5;     ///< the hand-held body: 19 mm diameter
  static constexpr double BodyLengthMm = 117.0;   ///< from the end of the taper to the back
  static constexpr double TotalLengthMm = TipLengthMm + TaperLengthMm + BodyLengthMm; ///< 175 mm
};

/// The default scalpel model: a CUSA-like handpiece in the PLUS model-catalogue convention, tip
/// at the origin and the instrument along -z, so the axis out through the tip is +z (what
/// Resources/CusaHandpiece.json states). A single closed surface of revolution (a lathe of the
/// profile: a flat tip face with a rounded rim whose centre is exactly the origin, the tip tube, a
/// smooth taper, the body, a rounded back face), consistently wound outward, 48 sectors, under
/// 2,000 triangles. Deterministic: Resources/CusaHandpiece.stl is this mesh as
/// vtkVesselMeshWriter writes it.
vtkSmartPointer<vtkPolyData> MakeCusaHandpiece();
} // namespace vp

#endif
