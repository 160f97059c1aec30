#ifndef vpPenetrationBenchmark_h
#define vpPenetrationBenchmark_h

#include "vpBenchmarkSupport.h"
#include "vpDistanceEngineSettings.h"

namespace vp
{
/// The instrument pushed into a vessel, where the full frame is slowest: a closed cylinder tool
/// (radius 1.5 mm, 40 mm long, tip face at its model origin, shaft along -z) advanced along +z
/// into a sphere vessel (radius 10 mm, portal_vein, at the origin) from 0.2 to 10 mm deep in
/// `poses` equal steps, two more spheres 40 mm to either side as the other classes. Per engine
/// (exact: the exact engine, FCL's whole surface and the exact penetration; with zbuffer settings
/// also the z-buffer's full frame from its layers), through the logic as a navigator runs it
/// (vtkVesselProximityLogic, one TrackingSession): the frame times per depth band (0-1, 1-3, 3-6,
/// 6-10 mm) and overall, median and p95, and the penetration against the closed forms (depth: the
/// push; volume: the cylinder's overlap with the sphere, integrated): the error, relative from
/// 1 mm deep, and whether each answer keeps its stated bound. Beside them, FCL's own penetration
/// depth of the two convex primitives (fcl::Cylinder into fcl::Sphere, EPA) and its time. Without a
/// Vulkan device the z-buffer's entry says so.
BenchJson BenchPenetration(int poses, const DistanceEngineSettings* zbuffer);
} // namespace vp

#endif
