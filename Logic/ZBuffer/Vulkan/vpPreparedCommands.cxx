#include "vpPreparedCommands.h"

namespace vp
{
PreparedCommands::PreparedCommands(VulkanContext& context, const std::function<void(VkCommandBuffer)>& record)
  : Context(context)
{
  VkCommandBufferAllocateInfo allocInfo{};
  allocInfo.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocInfo.commandPool = context.Pool();
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VulkanContext::Check(vkAllocateCommandBuffers(context.Handle(), &allocInfo, &this->Commands), "vkAllocateCommandBuffers");
  try
  {
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    VulkanContext::Check(vkBeginCommandBuffer(this->Commands, &begin), "vkBeginCommandBuffer");
    record(this->Commands);
    VulkanContext::Check(vkEndCommandBuffer(this->Commands), "vkEndCommandBuffer");
  }
  catch (...)
  {
    vkFreeCommandBuffers(context.Handle(), context.Pool(), 1, &this->Commands);
    throw;
  }
}

PreparedCommands::~PreparedCommands()
{
  vkFreeCommandBuffers(this->Context.Handle(), this->Context.Pool(), 1, &this->Commands);
}
} // namespace vp
