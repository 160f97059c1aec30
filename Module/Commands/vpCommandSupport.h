#ifndef vpCommandSupport_h
#define vpCommandSupport_h

#include "vpClock.h"
#include "vpQuantile.h"
#include "vpRunFolder.h" // CreateOutputFolder
#include "vpSceneRequest.h"
#include "vpSurfaceReport.h"
#include "vpVesselMeshSet.h"

#include <string>
#include <vector>

class vtkVesselDistanceEngine;
class vtkVesselProximityLogic;

namespace vp
{
/// DescribeSurfaceDefects on stderr, a line each prefixed with the command's name: after the
/// engine's Build(), so that no line comes before a refusal.
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);

/// What an opened scene tells the user (the engine's note, where the tip came from, the surfaces'
/// defects, a penetration that cannot be known), on stderr: said once everything is built and
/// checked, since a line before a refusal would make its one line two.
void ReportOpenedScene(
  const std::string& command, vtkVesselProximityLogic* proximity, const OpenedScene& scene, const std::string& scalpelFile);
} // namespace vp

#endif
