#include "vpBuiltInPhantom.h"

#include "vpAnalyticShapes.h"

namespace vp
{
std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> MakeBuiltInVessels()
{
  const double origin[3] = { 0, 0, 0 };
  const double superior[3] = { 0, 0, 1 };
  const double arteryCenter[3] = { 0, 0, 25 };
  const double left[3] = { 1, 0, 0 };
  const double veinCenter[3] = { 45, 30, -10 };
  return { { "portal_vein", MakeTorus(origin, superior, 30.0, 6.0, 96, 32) },
    { "hepatic_artery", MakeCappedCylinder(arteryCenter, left, 2.5, 80.0, 48) },
    { "hepatic_vein", MakeSphere(veinCenter, 10.0, 32, 64) } };
}
} // namespace vp
