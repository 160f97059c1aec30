#include "vpComputeKernel.h"

#include <string>

namespace vp
{
ComputeKernel::ComputeKernel(VulkanContext& context, const unsigned char* spirv, std::size_t spirvBytes,
  int storageBuffers, std::uint32_t pushConstantBytes)
  : Context(context)
  , Buffers(storageBuffers)
  , PushBytes(pushConstantBytes)
{
  VkDevice device = context.Handle();
  VkShaderModuleCreateInfo moduleInfo{};
  moduleInfo.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  moduleInfo.codeSize = spirvBytes;
  moduleInfo.pCode = reinterpret_cast<const std::uint32_t*>(spirv);
  VulkanContext::Check(vkCreateShaderModule(device, &moduleInfo, nullptr, &this->Module), "vkCreateShaderModule");

  std::vector<VkDescriptorSetLayoutBinding> bindings(storageBuffers);
  for (int i = 0; i < storageBuffers; ++i)
  {
    bindings[i] = {};
    bindings[i].binding = static_cast<std::uint32_t>(i);
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo setInfo{};
  setInfo.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  setInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  VulkanContext::Check(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &this->SetLayout), "vkCreateDescriptorSetLayout");

  VkPushConstantRange range{ VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes };
  VkPipelineLayoutCreateInfo layoutInfo{};
  layoutInfo.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &this->SetLayout;
  layoutInfo.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  layoutInfo.pPushConstantRanges = &range;
  VulkanContext::Check(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &this->Layout), "vkCreatePipelineLayout");

  VkComputePipelineCreateInfo pipelineInfo{};

  pipelineInfo.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pipelineInfo.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = this->Module;
  pipelineInfo.stage.pName = "main";
  pipelineInfo.layout = this->Layout;
  VulkanContext::Check(
    vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &this->Pipeline), "vkCreateComputePipelines");

  VkDescriptorPoolSize poolSize{ VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, static_cast<std::uint32_t>(storageBuffers) };
  VkDescriptorPoolCreateInfo poolInfo{};
  poolInfo.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &poolSize;
  VulkanContext::Check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &this->Pool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo allocInfo{};
  allocInfo.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  allocInfo.descriptorPool = this->Pool;
  allocInfo.descriptorSetCount = 1;
  allocInfo.pSetLayouts = &this->SetLayout;
  VulkanContext::Check(vkAllocateDescriptorSets(device, &allocInfo, &this->Set), "vkAllocateDescriptorSets");
}

ComputeKernel::~ComputeKernel()
{
  VkDevice device = this->Context.Handle();
  vkDestroyDescriptorPool(device, this->Pool, nullptr);
  vkDestroyPipeline(device, this->Pipeline, nullptr);
  vkDestroyPipelineLayout(device, this->Layout, nullptr);
  vkDestroyDescriptorSetLayout(device, this->SetLayout, nullptr);
  vkDestroyShaderModule(device, this->Module, nullptr);
}

void ComputeKernel::BindBuffers(const std::vector<VkBuffer>& buffers)
{
  if (static_cast<int>(buffers.size()) != this->Buffers)
  {
    throw DeviceError("ComputeKernel: " + std::to_string(buffers.size()) + " buffers bound where the shader declares " +
      std::to_string(this->Buffers));
  }
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i)
  {
    infos[i] = { buffers[i], 0, VK_WHOLE_SIZE };
    writes[i] = {};
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = this->Set;
    writes[i].dstBinding = static_cast<std::uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(this->Context.Handle(), static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void ComputeKernel::Bind(VkCommandBuffer cmd, const void* pushConstants) const
{
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, this->Pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, this->Layout, 0, 1, &this->Set, 0, nullptr);
  if (this->PushBytes)
  {
    vkCmdPushConstants(cmd, this->Layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, this->PushBytes, pushConstants);
  }
}

void ComputeKernel::Record(VkCommandBuffer cmd, const void* pushConstants, std::uint32_t x, std::uint32_t y,
  std::uint32_t z) const
{
  this->Bind(cmd, pushConstants);
  if (x && y && z)
  {
    vkCmdDispatch(cmd, x, y, z);
  }
}

void ComputeKernel::RecordIndirect(VkCommandBuffer cmd, const void* pushConstants, VkBuffer buffer, VkDeviceSize offset) const
{
  this->Bind(cmd, pushConstants);
  vkCmdDispatchIndirect(cmd, buffer, offset);
}

void ComputeKernel::Barrier(VkCommandBuffer cmd)
{
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  // Indirect reads too: a dispatch may take its size from what an earlier one wrote.
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
    VK_ACCESS_HOST_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT |
      VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
    0, 1, &barrier, 0, nullptr, 0, nullptr);
}
} // namespace vp
