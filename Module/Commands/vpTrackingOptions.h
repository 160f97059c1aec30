#ifndef vpTrackingOptions_h
#define vpTrackingOptions_h

#include "vpArguments.h"
#include "vpDangerLevels.h"
#include "vpScalpelLoader.h"
#include "vtkVesselProximityLogic.h"

#include <vtkSmartPointer.h>

#include <string>

namespace vp
{
/// --danger-mm C,W,D (default 10,5,2), validated: throws InputError naming the option.
DangerThresholds ParseDangerThresholds(const Arguments& args);
/// --tip X,Y,Z and --axis X,Y,Z in model coordinates, each optional.
ScalpelTipDefinition ParseTipDefinition(const Arguments& args);
/// --frame-budget-ms MS (default 16.7, one refresh at 60 Hz; 0 switches the check off): a finite
/// number, not negative; throws InputError naming the option.
double ParseFrameBudgetMs(const Arguments& args);
/// --hysteresis-mm MM (default 0.3; 0: none): how far past a threshold the distance must go to
/// leave a level (vtkScalpelTrackingLogic::SetHysteresisMm); throws InputError naming the option.
double ParseHysteresisMm(const Arguments& args);

/// The module logic with what the tracking options set, checked before any file is read: the
/// danger thresholds, the frame budget, the hysteresis, --no-surface, the engine of the given
/// --method (its device opened) and, for "both", the comparison with the exact engine.
vtkSmartPointer<vtkVesselProximityLogic> ConfigureTrackingLogic(const Arguments& args, const std::string& method);
} // namespace vp

#endif
