#include "vpVesselProximityDemoModule.h"

#include "vpLoadableModuleApi.h"
#include "vpModuleEntryPoint.h"
#include "vpDemoCommands.h"

std::string vpVesselProximityDemoModule::HelpText() const
{
  return "The VesselProximity module on data that needs no patient: a built-in liver phantom (portal vein, hepatic "
         "artery and hepatic veins) with a CUSA-like handpiece, the demo that tracks the handpiece into "
         "the vessels and writes its report and pictures, the module self-test, and the benchmarks that measure "
         "the engines beside their references (brute force, VTK's locator, FCL) as JSON.";
}

std::string vpVesselProximityDemoModule::AcknowledgementText() const
{
  return "Benchmarks measured beside VTK's vtkStaticCellLocator and FCL (the Flexible Collision Library); "
         "the live benchmark's tracker speaks OpenIGTLink through its library.";
}

// The demo module's C entry point, as the VesselProximity module's (vpVesselProximityModulePlugin.cxx).
extern "C" __attribute__((visibility("default"))) const vpModuleDescriptor* vpGetLoadableModule(void)
{
  return vp::ModuleEntryPoint<vpVesselProximityDemoModule, vp::DemoCommandTable>::Descriptor();
}
