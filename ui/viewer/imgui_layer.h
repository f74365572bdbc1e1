#pragma once
// Dear ImGui 1.86 on the viewer's swapchain: the palette and panels drawn on top of the cloud.
// The Vulkan backend of 1.86 needs a render pass (no dynamic rendering): one pass that loads the
// image the renderer has just copied the cloud into and leaves it ready to present, recorded by
// the renderer's present hook. Input comes from InputEvents, not from ImGui's GLFW backend, so a
// replayed script drives the palette as a user does. Not thread-safe: the main thread owns it.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <unordered_map>

#include "ui/viewer/input_event.h"

namespace plumb::gpu {
class Device;
class Instance;
class Swapchain;
struct SwapchainImage;
}  // namespace plumb::gpu

namespace plumb::viewer {

class ImguiLayer {
 public:
  // Creates the ImGui context and uploads the font (waits for the queue once).
  ImguiLayer(const gpu::Instance& instance, const gpu::Device& device, const gpu::Swapchain& swapchain);
  ~ImguiLayer();
  ImguiLayer(const ImguiLayer&) = delete;
  ImguiLayer& operator=(const ImguiLayer&) = delete;

  // ImGui 1.86 keeps input as state, not as a queue: feed a frame's events before beginFrame.
  void feed(const InputEvent& event);
  // Starts a frame of `width` x `height` window pixels, `delta_s` after the last one.
  void beginFrame(std::uint32_t width, std::uint32_t height, double delta_s);
  // Whether the palette has the mouse (a window under it, a drag started on it) or the keyboard
  // (a text field): then the view must not react. Valid after beginFrame.
  bool wantsMouse() const;
  bool wantsKeyboard() const;
  // Ends the frame's user interface (ImGui::Render); record() draws it.
  void endFrame();

  // The renderer's present hook: draws the frame's interface into `image` (arriving in
  // TRANSFER_DST_OPTIMAL) and leaves it in its presented_layout: PRESENT_SRC_KHR for the
  // window's, COLOR_ATTACHMENT_OPTIMAL for a headset's panel (of the window's format).
  void record(VkCommandBuffer commands, const gpu::SwapchainImage& image);

 private:
  struct Target {
    VkImageView view = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkExtent2D extent{};
  };
  const Target& targetFor(const gpu::SwapchainImage& image);
  void destroyTargets();

  const gpu::Device& device_;
  const gpu::Swapchain& swapchain_;
  VkDescriptorPool descriptors_ = VK_NULL_HANDLE;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  VkRenderPass panel_pass_ = VK_NULL_HANDLE;
  std::unordered_map<VkImage, Target> targets_;  // per swapchain image, dropped when it is rebuilt
  std::uint64_t targets_rebuild_ = 0;            // Swapchain::rebuilds() the targets were made for
  bool frame_ended_ = false;
};

}  // namespace plumb::viewer
