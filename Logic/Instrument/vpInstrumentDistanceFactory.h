#ifndef vpInstrumentDistanceFactory_h
#define vpInstrumentDistanceFactory_h

#include "vpInstrumentMethod.h"
#include "vtkScalpelSurfaceDistance.h"

#include <vtkSmartPointer.h>

class vtkExactVesselDistance;
class vtkPolyData;
class vtkVesselDistanceEngine;

namespace vp
{
/// The whole instrument's distance for the engine that answers the tip, built (nothing is built
/// in a frame's time): with InstrumentMethod::Automatic, from the engine's own layers (the
/// z-buffer's distance field, within a stated bound) when it is the z-buffer with its box fixed
/// around the vessels, else FCL (exact) on the exact engine; BoundingSpheres and Fcl as named.
/// exact: built, serving beside the engine (vtkExactVesselDistance::ServingBeside).
vtkSmartPointer<vtkScalpelSurfaceDistance> MakeInstrumentDistance(InstrumentMethod method, vtkVesselDistanceEngine* engine,
  vtkExactVesselDistance* exact, vtkPolyData* tool, double rangeMm);
} // namespace vp

#endif
