#ifndef vpPreparedCommands_h
#define vpPreparedCommands_h

#include "vpVulkanContext.h"

#include <functional>

namespace vp
{
/// A command buffer recorded once and submitted many times: what a query that runs every frame
/// needs, so that each frame costs a submission and a wait, not a recording. Everything it uses
/// (buffers, descriptor sets, push constants) must stay as it was when recorded; its owner records
/// a new one when any of it changes. Freed with the object; must not outlive its context.
class PreparedCommands
{
public:
  PreparedCommands(VulkanContext& context, const std::function<void(VkCommandBuffer)>& record);
  ~PreparedCommands();
  PreparedCommands(const PreparedCommands&) = delete;
  PreparedCommands& operator=(const PreparedCommands&) = delete;

  /// Submits the commands and waits for them.
  void Submit() { this->Context.SubmitRecorded(this->Commands); }
  /// Submits the commands in one of the context's slots without waiting (VulkanContext::StartRecorded):
  /// they must not be freed or submitted again before that slot is waited for.
  void Start(std::uint32_t slot) { this->Context.StartRecorded(this->Commands, slot); }

private:
  VulkanContext& Context;
  VkCommandBuffer Commands = VK_NULL_HANDLE;
};
} // namespace vp

#endif
