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
} // namespace vp

#endif
