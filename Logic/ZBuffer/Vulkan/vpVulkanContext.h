#ifndef vpVulkanContext_h
#define vpVulkanContext_h

#include "vpInputError.h" // DeviceError

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vp
{
/// What a Vulkan physical device calls itself.
struct VulkanDeviceInfo
{
  int Index = 0;
  std::string Name;
  std::string Type; // "discrete", "integrated", "virtual", "cpu", "other"
  std::uint32_t ApiVersion = 0;
};

/// A headless Vulkan logical device with one compute queue, on the process's one instance (kept
/// until the process ends, so that the driver is loaded once): no window, no display,
/// no surface extension. Mesa's lavapipe (a CPU device) works as well as a GPU.
///
/// Device choice: an empty selector takes a discrete GPU when there is one, then an integrated
/// one, then any other (lavapipe is a "cpu" device); a number picks that index of
/// ListDevices(); any other text picks the first device whose name contains it
/// (case-insensitive). Setting VP_VULKAN_VALIDATION=1 in the environment enables the Khronos
/// validation layer when it is installed and turns every message it prints into a DeviceError
/// on the next Submit().
class VulkanContext
{
public:
  explicit VulkanContext(const std::string& deviceSelector = std::string());
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  /// The devices the loader reports. Throws DeviceError when there is no Vulkan at all.
  static std::vector<VulkanDeviceInfo> ListDevices();

  const VulkanDeviceInfo& Device() const { return this->Info; }
  VkDevice Handle() const { return this->LogicalDevice; }
  VkPhysicalDevice Physical() const { return this->PhysicalDevice; }
  const VkPhysicalDeviceLimits& Limits() const { return this->Properties.limits; }

  /// A memory type index with all of required (and preferably all of preferred) among those in
  /// typeBits. Throws DeviceError when none fits.
  std::uint32_t FindMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
    VkMemoryPropertyFlags preferred = 0) const;

  /// The property flags of memory type `type`.
  VkMemoryPropertyFlags MemoryFlags(std::uint32_t type) const
  {
    return this->MemoryProperties.memoryTypes[type].propertyFlags;
  }

  /// Records commands with record(), submits them to the compute queue and waits for them.
  void Submit(const std::function<void(VkCommandBuffer)>& record);
  /// Submits an already recorded command buffer (vp::PreparedCommands) and waits for it. On a
  /// GPU the host polls the fence for up to SpinWaitMs before it sleeps on it: a sleeping
  /// thread is woken tens of microseconds after a short submission ends, which was most of a
  /// single query's time on an H100. A CPU device (lavapipe) needs the host's cores for the work
  /// itself, so there the host sleeps at once.
  void SubmitRecorded(VkCommandBuffer commands);
  /// Submissions that may be in flight at once, each in a slot of its own (fence and timestamps):
  /// with two, the device runs one while the host reads the one before and writes the next.
  static constexpr std::uint32_t Slots = 2;
  /// Submits a recorded command buffer in slot `slot` (< Slots) without waiting: the host goes on
  /// while the device works. The slot's previous submission is waited for first. The
  /// queue runs submissions in order; the commands themselves must order their work after the
  /// previous submission's where they share buffers (a barrier at the end of each does).
  void StartRecorded(VkCommandBuffer commands, std::uint32_t slot);
  /// Waits for slot `slot`'s submission (as SubmitRecorded); at once when none is in flight.
  void WaitRecorded(std::uint32_t slot);
  /// Waits for every slot's submission: before what they use is freed or rewritten. Throws as
  /// WaitRecorded, once every slot has been waited for.
  void WaitAll();
  /// Waits for the device to be idle and forgets every submission in flight, throwing nothing:
  /// for releasing resources from a destructor.
  void Drain() noexcept;
  /// How long the host polls a GPU's fence before it sleeps, in ms.
  static constexpr double SpinWaitMs = 2.0;
  /// Whether 64-bit atomics on storage buffers are enabled (VK_KHR_shader_atomic_int64 with
  /// shaderBufferInt64Atomics): lavapipe and the desktop GPUs have them.
  bool HasInt64Atomics() const { return this->Int64Atomics; }
  /// Whether the device is a CPU (lavapipe): its work runs on the host's own cores.
  bool IsCpuDevice() const { return this->Info.Type == "cpu"; }

  /// Timestamps on the device, up to StampsPerSlot a slot: Stamp(cmd, k, slot) recorded between
  /// the stages of a submission (after ResetStamps(cmd, slot), outside any render pass), then
  /// CopyStamps(cmd, slot, count, buffer, offset) writes the slot's first count (64-bit ticks,
  /// each of them stamped) where the host reads them once the submission is done, and
  /// StampsMs(ticks, from, to) is the device's time between stamps from and to, in ms; a negative
  /// value when the device has no compute timestamps. The copy, not vkGetQueryPoolResults:
  /// lavapipe's waits for the queue to empty, so reading one submission's stamps waited for the
  /// next one in flight as well. Each stamp waits for the commands before it, the previous
  /// submission's included: a submission queued behind another is timed from the other's end,
  /// not from its own arrival. On lavapipe a stamp between two dispatches costs some 50 µs.
  static constexpr std::uint32_t StampsPerSlot = 4;
  void ResetStamps(VkCommandBuffer cmd, std::uint32_t slot = 0) const;
  void Stamp(VkCommandBuffer cmd, std::uint32_t which, std::uint32_t slot = 0) const;
  void CopyStamps(VkCommandBuffer cmd, std::uint32_t slot, std::uint32_t count, VkBuffer buffer, VkDeviceSize offset) const;
  double StampsMs(const std::uint64_t* ticks, std::uint32_t from, std::uint32_t to) const;
  /// The pool prepared command buffers come from.
  VkCommandPool Pool() const { return this->CommandPool; }

  /// Throws DeviceError with what, the Vulkan result's name, when result is not VK_SUCCESS.
  static void Check(VkResult result, const char* what);

private:
  VkInstance Instance = VK_NULL_HANDLE; // the process's, shared by every context (never destroyed)
  VkDebugUtilsMessengerEXT Messenger = VK_NULL_HANDLE;
  VkPhysicalDevice PhysicalDevice = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties Properties{};
  VkPhysicalDeviceMemoryProperties MemoryProperties{};
  VkDevice LogicalDevice = VK_NULL_HANDLE;
  VkQueue Queue = VK_NULL_HANDLE;
  std::uint32_t QueueFamily = 0;
  VkCommandPool CommandPool = VK_NULL_HANDLE;
  VkCommandBuffer Commands = VK_NULL_HANDLE;
  VkFence Fences[Slots] = {};
  bool Pending[Slots] = {};
  VkQueryPool Stamps = VK_NULL_HANDLE; // StampsPerSlot a slot; null without compute timestamps
  std::uint64_t StampMask = ~0ull;     // the bits of a timestamp the queue keeps
  VulkanDeviceInfo Info;
  bool Int64Atomics = false;
  std::string ValidationMessage;

  static VKAPI_ATTR VkBool32 VKAPI_CALL OnValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
    VkDebugUtilsMessageTypeFlagsEXT type, const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);
  void Destroy();
  // The constructor's steps, in order.
  void StartValidationMessages();
  VkQueueFamilyProperties ChooseComputeQueue();
  void CreateLogicalDevice();
  void CreateCommandObjects(const VkQueueFamilyProperties& family);
};
} // namespace vp

#endif
