#include "vpVulkanContext.h"

#include "vpText.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <sstream>

namespace vp
{
namespace
{
const char* ResultName(VkResult r)
{
  switch (r)
  {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
    default: return "VkResult error";
  }
}

std::string TypeName(VkPhysicalDeviceType t)
{
  switch (t)
  {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

int Preference(VkPhysicalDeviceType t)
{
  switch (t)
  {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

bool WantsValidation()
{
  const char* v = std::getenv("VP_VULKAN_VALIDATION");
  return v && *v && std::strcmp(v, "0") != 0;
}

bool LayerAvailable(const char* name)
{
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
  {
    if (std::strcmp(l.layerName, name) == 0)
    {
      return true;
    }
  }
  return false;
}

// The instance the loader gives us, or a DeviceError that says why there is none. The loader
// answers VK_ERROR_INCOMPATIBLE_DRIVER when it finds no driver at all (no ICD installed, or
// VK_ICD_FILENAMES pointing at nothing).
VkInstance CreateInstance(bool validation)
{
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "VesselProximity";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  if (validation)
  {
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &extension;
  }
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult r = vkCreateInstance(&info, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
  {
    throw DeviceError("no Vulkan device: the Vulkan loader found no driver (VK_ERROR_INCOMPATIBLE_DRIVER); "
                      "install mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES");
  }
  if (r != VK_SUCCESS)
  {
    throw DeviceError(std::string("no Vulkan device: vkCreateInstance failed (") + ResultName(r) + ")");
  }
  return instance;
}

// One instance per process (two with the validation layer), made on first use and kept to the
// process's end, never destroyed: the Vulkan loader unloads the driver with the last instance,
// and lavapipe (Mesa 22.3.6-1+deb12u2) leaves behind, at each unload, a block it allocated once per
// load, which LeakSanitizer then reports as ours (128 bytes an engine, from an unloaded module
// nothing can name in a suppression). Loaded once, the driver also stops reloading LLVM for
// every engine. A failure is not kept: the next call tries again.
VkInstance SharedInstance(bool validation)
{
  static std::mutex lock;
  static VkInstance instances[2] = { VK_NULL_HANDLE, VK_NULL_HANDLE };
  std::lock_guard<std::mutex> guard(lock);
  VkInstance& instance = instances[validation ? 1 : 0];
  if (instance == VK_NULL_HANDLE)
  {
    instance = CreateInstance(validation);
  }
  return instance;
}

std::vector<VkPhysicalDevice> PhysicalDevices(VkInstance instance)
{
  std::uint32_t n = 0;
  VulkanContext::Check(vkEnumeratePhysicalDevices(instance, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(n);
  VulkanContext::Check(vkEnumeratePhysicalDevices(instance, &n, devices.data()), "vkEnumeratePhysicalDevices");
  devices.resize(n);
  if (devices.empty())
  {
    throw DeviceError("no Vulkan device: the Vulkan loader lists no physical device; "
                      "install mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES");
  }
  return devices;
}

VulkanDeviceInfo Describe(VkPhysicalDevice d, int index)
{
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(d, &p);
  VulkanDeviceInfo info;
  info.Index = index;
  info.Name = p.deviceName;
  info.Type = TypeName(p.deviceType);
  info.ApiVersion = p.apiVersion;
  return info;
}
} // namespace

void VulkanContext::Check(VkResult result, const char* what)
{
  if (result != VK_SUCCESS)
  {
    throw DeviceError(std::string("Vulkan: ") + what + " failed (" + ResultName(result) + ")");
  }
}

std::vector<VulkanDeviceInfo> VulkanContext::ListDevices()
{
  const auto devices = PhysicalDevices(SharedInstance(false));
  std::vector<VulkanDeviceInfo> out;
  for (std::size_t i = 0; i < devices.size(); ++i)
  {
    out.push_back(Describe(devices[i], static_cast<int>(i)));
  }
  return out;
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::OnValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
  VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data, void* self)
{
  auto* context = static_cast<VulkanContext*>(self);
  if ((severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) &&
    context->ValidationMessage.empty())
  {
    context->ValidationMessage = data->pMessage ? data->pMessage : "(no message)";
  }
  return VK_FALSE;
}

namespace
{
/// The device the selector picks (empty: the most capable kind; a number: that index; other text:
/// the first whose name holds it, any case), or DeviceError naming the choices.
int ChooseDevice(const std::vector<VkPhysicalDevice>& devices, const std::string& selector)
{
  int chosen = -1;
  if (selector.empty())
  {
    int best = 1 << 30;
    for (std::size_t i = 0; i < devices.size(); ++i)
    {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devices[i], &p);
      if (Preference(p.deviceType) < best)
      {
        best = Preference(p.deviceType);
        chosen = static_cast<int>(i);
      }
    }
  }
  else if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); }))
  {
    chosen = std::atoi(selector.c_str());
    if (chosen >= static_cast<int>(devices.size()))
    {
      chosen = -1;
    }
  }
  else
  {
    for (std::size_t i = 0; i < devices.size() && chosen < 0; ++i)
    {
      if (LowerCase(Describe(devices[i], 0).Name).find(LowerCase(selector)) != std::string::npos)
      {
        chosen = static_cast<int>(i);
      }
    }
  }
  if (chosen < 0)
  {
    std::ostringstream available;
    for (std::size_t i = 0; i < devices.size(); ++i)
    {
      available << (i ? ", " : "") << i << ": " << Describe(devices[i], static_cast<int>(i)).Name;
    }
    throw DeviceError("DeviceSelector", "no Vulkan device matches ", " '" + selector + "' (available: " + available.str() + ")");
  }
  return chosen;
}
} // namespace

VulkanContext::VulkanContext(const std::string& selector)
{
  const bool validation = WantsValidation() && LayerAvailable("VK_LAYER_KHRONOS_validation");
  this->Instance = SharedInstance(validation);
  try
  {
    if (validation)
    {
      this->StartValidationMessages();
    }
    const auto devices = PhysicalDevices(this->Instance);
    const int chosen = ChooseDevice(devices, selector);
    this->PhysicalDevice = devices[chosen];
    this->Info = Describe(this->PhysicalDevice, chosen);
    vkGetPhysicalDeviceProperties(this->PhysicalDevice, &this->Properties);
    vkGetPhysicalDeviceMemoryProperties(this->PhysicalDevice, &this->MemoryProperties);
    const VkQueueFamilyProperties family = this->ChooseComputeQueue();
    this->CreateLogicalDevice();
    this->CreateCommandObjects(family);
  }
  catch (...)
  {
    this->Destroy();
    throw;
  }
}

void VulkanContext::StartValidationMessages()
{
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &VulkanContext::OnValidationMessage;
  info.pUserData = this;
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
    vkGetInstanceProcAddr(this->Instance, "vkCreateDebugUtilsMessengerEXT"));
  if (create)
  {
    Check(create(this->Instance, &info, nullptr, &this->Messenger), "vkCreateDebugUtilsMessengerEXT");
  }
}

VkQueueFamilyProperties VulkanContext::ChooseComputeQueue()
{
  std::uint32_t nFamilies = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(this->PhysicalDevice, &nFamilies, nullptr);
  std::vector<VkQueueFamilyProperties> families(nFamilies);
  vkGetPhysicalDeviceQueueFamilyProperties(this->PhysicalDevice, &nFamilies, families.data());
  bool found = false;
  for (std::uint32_t i = 0; i < nFamilies && !found; ++i)
  {
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)
    {
      this->QueueFamily = i;
      found = true;
    }
  }
  if (!found)
  {
    throw DeviceError("Vulkan device '" + this->Info.Name + "' has no compute queue");
  }
  return families[this->QueueFamily];
}

void VulkanContext::CreateLogicalDevice()
{
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{};
  queueInfo.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queueInfo.queueFamilyIndex = this->QueueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{};
  deviceInfo.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  // 64-bit buffer atomics, where the device has them (through the extension: the instance asks
  // for Vulkan 1.1, where they are not core).
  const char* atomicInt64 = VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME;
  std::uint32_t nExtensions = 0;
  vkEnumerateDeviceExtensionProperties(this->PhysicalDevice, nullptr, &nExtensions, nullptr);
  std::vector<VkExtensionProperties> extensions(nExtensions);
  vkEnumerateDeviceExtensionProperties(this->PhysicalDevice, nullptr, &nExtensions, extensions.data());
  VkPhysicalDeviceShaderAtomicInt64FeaturesKHR int64Atomics{};
  int64Atomics.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES_KHR;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &int64Atomics;
  VkPhysicalDeviceFeatures enabled{};
  VkPhysicalDeviceShaderAtomicInt64FeaturesKHR enabledAtomics{};
  enabledAtomics.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES_KHR;
  if (std::any_of(extensions.begin(), extensions.end(),
        [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, atomicInt64) == 0; }))
  {
    vkGetPhysicalDeviceFeatures2(this->PhysicalDevice, &features);
    if (features.features.shaderInt64 && int64Atomics.shaderBufferInt64Atomics)
    {
      enabled.shaderInt64 = VK_TRUE;
      enabledAtomics.shaderBufferInt64Atomics = VK_TRUE;
      deviceInfo.pNext = &enabledAtomics;
      deviceInfo.pEnabledFeatures = &enabled;
      deviceInfo.enabledExtensionCount = 1;
      deviceInfo.ppEnabledExtensionNames = &atomicInt64;
      this->Int64Atomics = true;
    }
  }
  Check(vkCreateDevice(this->PhysicalDevice, &deviceInfo, nullptr, &this->LogicalDevice), "vkCreateDevice");
  vkGetDeviceQueue(this->LogicalDevice, this->QueueFamily, 0, &this->Queue);

}

void VulkanContext::CreateCommandObjects(const VkQueueFamilyProperties& family)
{
  VkCommandPoolCreateInfo poolInfo{};

  poolInfo.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = this->QueueFamily;
  Check(vkCreateCommandPool(this->LogicalDevice, &poolInfo, nullptr, &this->CommandPool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo allocInfo{};
  allocInfo.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocInfo.commandPool = this->CommandPool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  Check(vkAllocateCommandBuffers(this->LogicalDevice, &allocInfo, &this->Commands), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fenceInfo{};
  fenceInfo.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  for (VkFence& fence : this->Fences)
  {
    Check(vkCreateFence(this->LogicalDevice, &fenceInfo, nullptr, &fence), "vkCreateFence");
  }
  if (family.timestampValidBits > 0 && this->Properties.limits.timestampPeriod > 0.0f)
  {
    VkQueryPoolCreateInfo stampInfo{};
    stampInfo.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    stampInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    stampInfo.queryCount = StampsPerSlot * Slots;
    Check(vkCreateQueryPool(this->LogicalDevice, &stampInfo, nullptr, &this->Stamps), "vkCreateQueryPool");
    const std::uint32_t valid = family.timestampValidBits;
    this->StampMask = valid >= 64 ? ~0ull : (1ull << valid) - 1ull;
  }
}

VulkanContext::~VulkanContext()
{
  this->Destroy();
}

void VulkanContext::Destroy()
{
  if (this->LogicalDevice)
  {
    vkDeviceWaitIdle(this->LogicalDevice);
    for (VkFence fence : this->Fences)
    {
      if (fence)
      {
        vkDestroyFence(this->LogicalDevice, fence, nullptr);
      }
    }
    if (this->Stamps)
    {
      vkDestroyQueryPool(this->LogicalDevice, this->Stamps, nullptr);
    }
    if (this->CommandPool)
    {
      vkDestroyCommandPool(this->LogicalDevice, this->CommandPool, nullptr);
    }
    vkDestroyDevice(this->LogicalDevice, nullptr);
  }
  if (this->Messenger)
  {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(this->Instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy)
    {
      destroy(this->Instance, this->Messenger, nullptr);
    }
  }
  // The instance is the process's (SharedInstance): it stays.
  for (std::uint32_t slot = 0; slot < Slots; ++slot)
  {
    this->Fences[slot] = VK_NULL_HANDLE;
    this->Pending[slot] = false;
  }
  this->Stamps = VK_NULL_HANDLE;
  this->CommandPool = VK_NULL_HANDLE;
  this->LogicalDevice = VK_NULL_HANDLE;
  this->Messenger = VK_NULL_HANDLE;
  this->Instance = VK_NULL_HANDLE;
}

std::uint32_t VulkanContext::FindMemoryType(
  std::uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const
{
  for (const VkMemoryPropertyFlags want : { required | preferred, required })
  {
    for (std::uint32_t i = 0; i < this->MemoryProperties.memoryTypeCount; ++i)
    {
      if ((typeBits & (1u << i)) && (this->MemoryProperties.memoryTypes[i].propertyFlags & want) == want)
      {
        return i;
      }
    }
  }
  throw DeviceError("Vulkan device '" + this->Info.Name + "' has no suitable memory type");
}

void VulkanContext::Submit(const std::function<void(VkCommandBuffer)>& record)
{
  this->WaitAll(); // its command buffer and slot 0 may be in use
  Check(vkResetCommandBuffer(this->Commands, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  Check(vkBeginCommandBuffer(this->Commands, &begin), "vkBeginCommandBuffer");
  record(this->Commands);
  Check(vkEndCommandBuffer(this->Commands), "vkEndCommandBuffer");
  this->SubmitRecorded(this->Commands);
}

void VulkanContext::SubmitRecorded(VkCommandBuffer commands)
{
  this->StartRecorded(commands, 0);
  this->WaitRecorded(0);
}

void VulkanContext::StartRecorded(VkCommandBuffer commands, std::uint32_t slot)
{
  this->WaitRecorded(slot); // its fence may not be reset while in use
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  Check(vkResetFences(this->LogicalDevice, 1, &this->Fences[slot]), "vkResetFences");
  Check(vkQueueSubmit(this->Queue, 1, &submit, this->Fences[slot]), "vkQueueSubmit");
  this->Pending[slot] = true;
}

void VulkanContext::WaitRecorded(std::uint32_t slot)
{
  if (!this->Pending[slot])
  {
    return;
  }
  VkResult status = VK_NOT_READY;
  if (!this->IsCpuDevice())
  {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(SpinWaitMs);
    while ((status = vkGetFenceStatus(this->LogicalDevice, this->Fences[slot])) == VK_NOT_READY &&
      std::chrono::steady_clock::now() < deadline)
    {
    }
  }
  if (status != VK_SUCCESS)
  {
    Check(vkWaitForFences(this->LogicalDevice, 1, &this->Fences[slot], VK_TRUE, UINT64_MAX), "vkWaitForFences");
  }
  this->Pending[slot] = false;
  if (!this->ValidationMessage.empty())
  {
    const std::string message = this->ValidationMessage;
    this->ValidationMessage.clear();
    throw DeviceError("Vulkan validation: " + message);
  }
}

void VulkanContext::WaitAll()
{
  // Every slot is waited for, even when one's wait throws: the caller frees what they use.
  std::exception_ptr first;
  for (std::uint32_t slot = 0; slot < Slots; ++slot)
  {
    try
    {
      this->WaitRecorded(slot);
    }
    catch (...)
    {
      this->Pending[slot] = false;
      first = first ? first : std::current_exception();
    }
  }
  if (first)
  {
    std::rethrow_exception(first);
  }
}

void VulkanContext::Drain() noexcept
{
  vkDeviceWaitIdle(this->LogicalDevice); // a lost device returns at once: nothing runs any more
  for (bool& pending : this->Pending)
  {
    pending = false;
  }
}

void VulkanContext::ResetStamps(VkCommandBuffer cmd, std::uint32_t slot) const
{
  if (this->Stamps)
  {
    vkCmdResetQueryPool(cmd, this->Stamps, StampsPerSlot * slot, StampsPerSlot);
  }
}

void VulkanContext::Stamp(VkCommandBuffer cmd, std::uint32_t which, std::uint32_t slot) const
{
  if (this->Stamps)
  {
    // At the bottom of the pipe: after every earlier command, a queued submission's before it.
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, this->Stamps, StampsPerSlot * slot + which);
  }
}

void VulkanContext::CopyStamps(
  VkCommandBuffer cmd, std::uint32_t slot, std::uint32_t count, VkBuffer buffer, VkDeviceSize offset) const
{
  if (this->Stamps)
  {
    vkCmdCopyQueryPoolResults(cmd, this->Stamps, StampsPerSlot * slot, count, buffer, offset, sizeof(std::uint64_t),
      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  }
}

double VulkanContext::StampsMs(const std::uint64_t* ticks, std::uint32_t from, std::uint32_t to) const
{
  if (!this->Stamps)
  {
    return -1.0;
  }
  return static_cast<double>((ticks[to] - ticks[from]) & this->StampMask) * this->Properties.limits.timestampPeriod * 1e-6;
}
} // namespace vp
