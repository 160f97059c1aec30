#ifndef vpBuiltInPhantom_h
#define vpBuiltInPhantom_h

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <utility>
#include <vector>

namespace vp
{
/// The built-in vessels for a first run without data, in LPS mm: portal_vein, a torus (ring
/// 30 mm, tube 6 mm, centre 0,0,0, axis S); hepatic_artery, a capped cylinder (radius 2.5 mm,
/// length 80 mm, centre 0,0,25, axis L); hepatic_vein, a sphere (radius 10 mm, centre
/// 45,30,-10). Closed and outward; a stand-in until the procedural liver phantom exists.
std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> MakeBuiltInVessels();
} // namespace vp

#endif
