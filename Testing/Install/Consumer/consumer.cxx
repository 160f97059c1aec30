// The smallest embedding of the logic: one vessel in memory, one tip, the exact engine's answer.
// Prints the distance; exits 1 unless it is the sphere's analytic distance within its facets.
#include "vpDistanceEngineFactory.h"
#include "vpTipDistanceQuery.h"

#include <vtkNew.h>
#include <vtkSphereSource.h>

#include <cmath>
#include <cstdio>

int main()
{
  vtkNew<vtkSphereSource> sphere; // radius 10 mm at the origin
  sphere->SetRadius(10.0);
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(64);
  sphere->Update();
  vp::TipDistanceRequest request;
  request.Engine = vp::MakeDistanceEngine(vp::DistanceEngineSettings());
  request.Vessels = { { "portal_vein", "", sphere->GetOutput(), std::nullopt } };
  request.TipsMm = { { 0.0, 0.0, 25.0 } };
  const vp::TipDistanceAnswer answer = vp::ComputeTipDistances(request);
  const double distance = answer.Results.at(0).Classes.at(0).DistanceMm;
  std::printf("portal_vein %.6f mm from (0,0,25), method %s\n", distance, request.Engine->GetMethodName());
  // A pole of the sphere is a vertex: 15 mm exactly.
  return std::abs(distance - 15.0) < 1e-9 ? 0 : 1;
}
