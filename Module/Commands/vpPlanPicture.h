#ifndef vpPlanPicture_h
#define vpPlanPicture_h

#include "vpApproachPlan.h"

#include <string>

class vtkPolyData;
class vtkVesselProximityLogic;

namespace vp
{
class ModuleServices;

/// plan.png: the vessels (and the liver, translucent), the target, and the planned approach as a
/// tube along the tip's path coloured by the danger level at each pose (the module's level
/// colours), the instrument drawn at the entry (later, its shaft would hide the path behind its
/// tip); the safest approach of a search beside it, thinner; a caption with the clearance. Seen from the side of the path (from the
/// patient's front when the path allows). Rendered off-screen through the module's view: needs a
/// display (the caller makes sure of one).
struct PlanPictureRequest
{
  vtkVesselProximityLogic* Logic = nullptr; ///< its scene open
  vtkPolyData* Liver = nullptr;             ///< may be null
  vtkPolyData* Target = nullptr;
  const ApproachPlan* Plan = nullptr;
  std::string File;
};

void RenderPlanPicture(const ModuleServices& module, const PlanPictureRequest& request);
} // namespace vp

#endif
