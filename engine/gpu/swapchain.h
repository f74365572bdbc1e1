#pragma once
// A window's swapchain that survives resizes, out-of-date surfaces and minimised windows. The
// window layer (GLFW in ui/) makes the surface and says how large its framebuffer is; this owns
// the surface from then on.
//
// Each frame: acquire() an image (nothing while the window is minimised: skip the frame), record
// work that waits on its `acquired` semaphore, writes the image and leaves it in
// PRESENT_SRC_KHR, signalling `rendered`; then present(). A changed size or an out-of-date or
// suboptimal swapchain is rebuilt at the next acquire, after the device is idle (resizes are
// rare; the simplicity is worth a stall). Not thread-safe: the render thread owns it.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace plumb::gpu {

class Device;
class Instance;

// An image a frame is presented to: a window's (Swapchain::acquire) or an OpenXR runtime's, an
// eye of a headset (ui/xr), which has no semaphores and goes back in COLOR_ATTACHMENT_OPTIMAL.
struct SwapchainImage {
  VkImage image;
  std::uint32_t index;
  VkExtent2D extent;
  VkFormat format;
  VkSemaphore acquired;  // wait on it before writing the image; VK_NULL_HANDLE: nothing to wait for
  VkSemaphore rendered;  // signal it when the image is ready to present; VK_NULL_HANDLE: none
  VkImageLayout presented_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;  // the layout it is handed on in
  bool decorated = true;  // the renderer's present hook draws on it (the window's interface)
  // A headset eye's depth image (XR_KHR_composition_layer_depth), the same size, D32_SFLOAT or
  // D16_UNORM: the renderer writes the frame's depth into it and hands it on in
  // DEPTH_STENCIL_ATTACHMENT_OPTIMAL. VK_NULL_HANDLE: none.
  VkImage depth = VK_NULL_HANDLE;
  VkFormat depth_format = VK_FORMAT_UNDEFINED;
};

class Swapchain {
 public:
  // `framebuffer_size`: the window's framebuffer in pixels now (0 x 0 when minimised).
  Swapchain(const Instance& instance, const Device& device, VkSurfaceKHR surface,
            std::function<VkExtent2D()> framebuffer_size);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // The next image, or nothing while the window is minimised. Throws DeviceLost, plumb::Error.
  std::optional<SwapchainImage> acquire();
  // Queues `image` for presentation after its `rendered` semaphore.
  void present(const SwapchainImage& image);

  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return format_; }  // known from construction, before the first build
  std::uint32_t imageCount() const { return static_cast<std::uint32_t>(images_.size()); }
  // Whether the images may be copied from (TRANSFER_SRC), for screenshots.
  bool readable() const { return readable_; }
  std::uint64_t rebuilds() const { return rebuilds_; }  // since construction, the first build excluded

 private:
  void build();
  void destroyImagesAndSemaphores();

  VkInstance instance_;
  const Device& device_;
  VkSurfaceKHR surface_;
  std::function<VkExtent2D()> framebuffer_size_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkSurfaceFormatKHR surface_format_;  // chosen once: a render pass made for it stays valid
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> acquired_;  // a ring, one more than the images
  std::vector<VkSemaphore> rendered_;  // one per image
  std::size_t next_acquired_ = 0;
  bool stale_ = true;  // rebuild before the next acquire
  bool readable_ = false;
  std::uint64_t builds_ = 0, rebuilds_ = 0;
};

}  // namespace plumb::gpu
