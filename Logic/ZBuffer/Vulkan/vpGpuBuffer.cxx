#include "vpGpuBuffer.h"

#include <cstring>
#include <memory>

namespace vp
{
GpuBuffer::GpuBuffer(VulkanContext& context, VkDeviceSize bytes, Placement placement)
  : Context(context)
  , Bytes(bytes)
{
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = bytes > 0 ? bytes : 4;
  // Any buffer may also hold the sizes of an indirect dispatch (the query's, written by the host).
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
    VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VulkanContext::Check(vkCreateBuffer(context.Handle(), &info, nullptr, &this->Buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(context.Handle(), this->Buffer, &req);
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = req.size;
  std::uint32_t type;
  if (placement == Placement::Device)
  {
    type = context.FindMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  }
  else if (placement == Placement::HostToDevice)
  {
    type = context.FindMemoryType(req.memoryTypeBits,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  }
  else
  {
    type = context.FindMemoryType(req.memoryTypeBits,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  }
  alloc.memoryTypeIndex = type;
  const VkResult r = vkAllocateMemory(context.Handle(), &alloc, nullptr, &this->Memory);
  if (r != VK_SUCCESS)
  {
    vkDestroyBuffer(context.Handle(), this->Buffer, nullptr);
    VulkanContext::Check(r, "vkAllocateMemory");
  }
  vkBindBufferMemory(context.Handle(), this->Buffer, this->Memory, 0);
  const VkMemoryPropertyFlags flags = context.MemoryFlags(type);
  if ((flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))
  {
    VulkanContext::Check(vkMapMemory(context.Handle(), this->Memory, 0, VK_WHOLE_SIZE, 0, &this->Mapping), "vkMapMemory");
  }
}

GpuBuffer::~GpuBuffer()
{
  if (this->Mapping)
  {
    vkUnmapMemory(this->Context.Handle(), this->Memory);
  }
  vkDestroyBuffer(this->Context.Handle(), this->Buffer, nullptr);
  vkFreeMemory(this->Context.Handle(), this->Memory, nullptr);
}

void GpuBuffer::Upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset)
{
  if (bytes == 0)
  {
    return;
  }
  if (this->Mapping)
  {
    std::memcpy(static_cast<char*>(this->Mapping) + offset, data, bytes);
    return;
  }
  GpuBuffer staging(this->Context, bytes, Placement::Host);
  std::memcpy(staging.Mapped(), data, bytes);
  this->Context.Submit([&](VkCommandBuffer cmd) {
    VkBufferCopy region{ 0, offset, bytes };
    vkCmdCopyBuffer(cmd, staging.Handle(), this->Buffer, 1, &region);
  });
}
} // namespace vp
