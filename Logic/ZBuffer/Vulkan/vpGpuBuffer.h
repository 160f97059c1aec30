#ifndef vpGpuBuffer_h
#define vpGpuBuffer_h

#include "vpVulkanContext.h"

#include <cstddef>

namespace vp
{
/// A storage buffer and its memory. "Device" buffers live where the device computes fastest and
/// are filled through a staging copy when the host cannot see them (a GPU) or directly when it
/// can (lavapipe); "Host" buffers are mapped for reading results back; "HostToDevice" buffers are
/// mapped and written by the host for the device to read many times, in device memory the host
/// can see when there is such (a GPU's BAR), else in host memory: a GPU that read them from host
/// memory would cross the bus once per read.
class GpuBuffer
{
public:
  enum class Placement
  {
    Device,
    Host,
    HostToDevice
  };
  GpuBuffer(VulkanContext& context, VkDeviceSize bytes, Placement placement);
  ~GpuBuffer();
  GpuBuffer(const GpuBuffer&) = delete;
  GpuBuffer& operator=(const GpuBuffer&) = delete;

  VkBuffer Handle() const { return this->Buffer; }
  VkDeviceSize Size() const { return this->Bytes; }
  /// The mapped memory; null unless the buffer is host-visible.
  void* Mapped() const { return this->Mapping; }
  /// Copies bytes into the buffer at offset and waits until the copy is done.
  void Upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

private:
  VulkanContext& Context;
  VkBuffer Buffer = VK_NULL_HANDLE;
  VkDeviceMemory Memory = VK_NULL_HANDLE;
  VkDeviceSize Bytes = 0;
  void* Mapping = nullptr;
};
} // namespace vp

#endif
