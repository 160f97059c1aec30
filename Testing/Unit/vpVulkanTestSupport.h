#ifndef vpVulkanTestSupport_h
#define vpVulkanTestSupport_h

#include "vpVulkanContext.h"

#include <gtest/gtest.h>

/// Skips the test, saying why, when this machine has no Vulkan device.
#define VP_REQUIRE_VULKAN()                                                                                            \
  do                                                                                                                   \
  {                                                                                                                    \
    try                                                                                                                \
    {                                                                                                                  \
      vp::VulkanContext::ListDevices();                                                                                \
    }                                                                                                                  \
    catch (const vp::DeviceError& e)                                                                                   \
    {                                                                                                                  \
      GTEST_SKIP() << "z-buffer engine not tested: " << e.what();                                                     \
    }                                                                                                                  \
  } while (0)

#endif
