#ifndef vpTrackingOptions_h
#define vpTrackingOptions_h

#include "vpArguments.h"
#include "vpDangerLevels.h"
#include "vpScalpelLoader.h"

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
} // namespace vp

#endif
