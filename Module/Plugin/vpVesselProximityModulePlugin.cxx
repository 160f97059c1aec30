// The C entry point of the VesselProximity module library: the host program finds it with
// dlsym and learns the module's metadata and commands from the descriptor.
#include "vpCommandTable.h"
#include "vpModuleEntryPoint.h"
#include "vpVesselProximityModule.h"

extern "C" __attribute__((visibility("default"))) const vpModuleDescriptor* vpGetLoadableModule(void)
{
  return vp::ModuleEntryPoint<vpVesselProximityModule, vp::CommandTable>::Descriptor();
}
