#ifndef vpComputeKernel_h
#define vpComputeKernel_h

#include "vpVulkanContext.h"

#include <cstddef>
#include <vector>

namespace vp
{
/// One compute shader ready to dispatch: its pipeline, and one descriptor set of storage buffers
/// bound at bindings 0..n-1 of set 0, with push constants for the per-dispatch parameters.
class ComputeKernel
{
public:
  ComputeKernel(VulkanContext& context, const unsigned char* spirv, std::size_t spirvBytes, int storageBuffers,
    std::uint32_t pushConstantBytes);
  ~ComputeKernel();
  ComputeKernel(const ComputeKernel&) = delete;
  ComputeKernel& operator=(const ComputeKernel&) = delete;

  /// Binds these buffers, whole, at bindings 0, 1, ...
  void BindBuffers(const std::vector<VkBuffer>& buffers);
  /// Records the dispatch with these push constants into cmd.
  void Record(VkCommandBuffer cmd, const void* pushConstants, std::uint32_t groupsX, std::uint32_t groupsY = 1,
    std::uint32_t groupsZ = 1) const;

  /// Records a dispatch whose workgroup counts are read, when it runs, from the
  /// VkDispatchIndirectCommand at offset in buffer (so that a recorded submission can change its
  /// size: the host writes the counts before each submission).
  void RecordIndirect(VkCommandBuffer cmd, const void* pushConstants, VkBuffer buffer, VkDeviceSize offset) const;
  /// Makes the shader writes recorded so far visible to later shaders, transfers and indirect
  /// dispatches.
  static void Barrier(VkCommandBuffer cmd);

private:
  /// Binds the pipeline and the descriptor set, and pushes the constants.
  void Bind(VkCommandBuffer cmd, const void* pushConstants) const;

  VulkanContext& Context;
  int Buffers = 0;
  std::uint32_t PushBytes = 0;
  VkShaderModule Module = VK_NULL_HANDLE;
  VkDescriptorSetLayout SetLayout = VK_NULL_HANDLE;
  VkPipelineLayout Layout = VK_NULL_HANDLE;
  VkPipeline Pipeline = VK_NULL_HANDLE;
  VkDescriptorPool Pool = VK_NULL_HANDLE;
  VkDescriptorSet Set = VK_NULL_HANDLE;
};
} // namespace vp

#endif
