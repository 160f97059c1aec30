#ifndef vpCommandSupport_h
#define vpCommandSupport_h

#include "vpClock.h"
#include "vpQuantile.h"
#include "vpRunFolder.h" // CreateOutputFolder
#include "vpSurfaceReport.h"
#include "vpVesselMeshSet.h"

#include <string>
#include <vector>

class vtkVesselDistanceEngine;

namespace vp
{
/// DescribeSurfaceDefects on stderr, a line each prefixed with the command's name: after the
/// engine's Build(), so that no line comes before a refusal.
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);
} // namespace vp

#endif
