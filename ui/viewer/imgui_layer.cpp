#include "ui/viewer/imgui_layer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_vulkan.h>

#include <array>
#include <cassert>

#include "engine/core/error.h"
#include "engine/gpu/commands.h"
#include "engine/gpu/device.h"
#include "engine/gpu/image.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/swapchain.h"
#include "engine/gpu/timeline.h"
#include "engine/gpu/vk_check.h"

namespace plumb::viewer {
namespace {

void checkImgui(VkResult result) {
  gpu::check(result, "Dear ImGui's Vulkan backend");
}

// One pass for the window (loading the cloud the renderer copied in, leaving the image ready to
// present) and one for a headset's panel (loading its cleared image, leaving it for the
// runtime): compatible passes, so that the backend's one pipeline draws in both.
VkRenderPass createRenderPass(VkDevice device, VkFormat format, VkImageLayout final_layout) {
  VkAttachmentDescription colour{};
  colour.format = format;
  colour.samples = VK_SAMPLE_COUNT_1_BIT;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the cloud the renderer copied in
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  colour.finalLayout = final_layout;
  const VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &reference;
  // After the renderer's copy into the image.
  VkSubpassDependency after_copy{};
  after_copy.srcSubpass = VK_SUBPASS_EXTERNAL;
  after_copy.dstSubpass = 0;
  after_copy.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  after_copy.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  after_copy.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  after_copy.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  create.attachmentCount = 1;
  create.pAttachments = &colour;
  create.subpassCount = 1;
  create.pSubpasses = &subpass;
  create.dependencyCount = 1;
  create.pDependencies = &after_copy;
  VkRenderPass pass = VK_NULL_HANDLE;
  gpu::check(vkCreateRenderPass(device, &create, nullptr, &pass), "vkCreateRenderPass");
  return pass;
}

// ImGui 1.86 reads keys from io.KeysDown[] through io.KeyMap: GLFW's codes are the indices.
void mapKeys(ImGuiIO& io) {
  const std::array<std::pair<ImGuiKey, int>, 22> keys{{
      {ImGuiKey_Tab, GLFW_KEY_TAB},
      {ImGuiKey_LeftArrow, GLFW_KEY_LEFT},
      {ImGuiKey_RightArrow, GLFW_KEY_RIGHT},
      {ImGuiKey_UpArrow, GLFW_KEY_UP},
      {ImGuiKey_DownArrow, GLFW_KEY_DOWN},
      {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP},
      {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN},
      {ImGuiKey_Home, GLFW_KEY_HOME},
      {ImGuiKey_End, GLFW_KEY_END},
      {ImGuiKey_Insert, GLFW_KEY_INSERT},
      {ImGuiKey_Delete, GLFW_KEY_DELETE},
      {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
      {ImGuiKey_Space, GLFW_KEY_SPACE},
      {ImGuiKey_Enter, GLFW_KEY_ENTER},
      {ImGuiKey_Escape, GLFW_KEY_ESCAPE},
      {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER},
      {ImGuiKey_A, GLFW_KEY_A},
      {ImGuiKey_C, GLFW_KEY_C},
      {ImGuiKey_V, GLFW_KEY_V},
      {ImGuiKey_X, GLFW_KEY_X},
      {ImGuiKey_Y, GLFW_KEY_Y},
      {ImGuiKey_Z, GLFW_KEY_Z},
  }};
  for (const auto& [imgui_key, glfw_key] : keys) io.KeyMap[imgui_key] = glfw_key;
}

}  // namespace

ImguiLayer::ImguiLayer(const gpu::Instance& instance, const gpu::Device& device, const gpu::Swapchain& swapchain)
    : device_(device), swapchain_(swapchain) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is the app's, not a file beside the working directory
  mapKeys(io);
  ImGui::StyleColorsDark();

  const std::array<VkDescriptorPoolSize, 1> sizes{{{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}}};
  VkDescriptorPoolCreateInfo pool{};
  pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool.maxSets = 8;
  pool.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pool.pPoolSizes = sizes.data();
  gpu::check(vkCreateDescriptorPool(device.handle(), &pool, nullptr, &descriptors_), "vkCreateDescriptorPool");
  render_pass_ = createRenderPass(device.handle(), swapchain.format(), VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  panel_pass_ = createRenderPass(device.handle(), swapchain.format(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = instance.handle();
  init.PhysicalDevice = device.physical();
  init.Device = device.handle();
  init.QueueFamily = device.queueFamily();
  init.Queue = device.queue();
  init.DescriptorPool = descriptors_;
  init.Subpass = 0;
  init.MinImageCount = 2;
  // The backend's ring of vertex buffers, one a draw: the window's image and a headset's panel
  // each draw a frame's interface, and frames overlap on the GPU; 8 outlasts both.
  init.ImageCount = std::max<std::uint32_t>(8, swapchain.imageCount());
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = checkImgui;
  if (!ImGui_ImplVulkan_Init(&init, render_pass_)) throw Error("Dear ImGui's Vulkan backend failed to start");

  gpu::CommandPool pool_for_fonts(device, "imgui fonts");
  const gpu::TimelineSemaphore uploaded(device);
  VkCommandBuffer commands = pool_for_fonts.begin();
  ImGui_ImplVulkan_CreateFontsTexture(commands);
  gpu::submit(device, commands, uploaded, 1);
  uploaded.wait(1, UINT64_MAX);
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImguiLayer::~ImguiLayer() {
  vkDeviceWaitIdle(device_.handle());
  ImGui_ImplVulkan_Shutdown();
  ImGui::DestroyContext();
  destroyTargets();
  vkDestroyRenderPass(device_.handle(), render_pass_, nullptr);
  vkDestroyRenderPass(device_.handle(), panel_pass_, nullptr);
  vkDestroyDescriptorPool(device_.handle(), descriptors_, nullptr);
}

void ImguiLayer::feed(const InputEvent& event) {
  ImGuiIO& io = ImGui::GetIO();
  switch (event.kind) {
    case InputEvent::Kind::kMouseMove:
      io.MousePos = ImVec2(static_cast<float>(event.x), static_cast<float>(event.y));
      break;
    case InputEvent::Kind::kMouseButton:
      io.MousePos = ImVec2(static_cast<float>(event.x), static_cast<float>(event.y));
      if (event.button >= 0 && event.button < IM_ARRAYSIZE(io.MouseDown)) io.MouseDown[event.button] = event.pressed;
      break;
    case InputEvent::Kind::kWheel:
      io.MouseWheel += static_cast<float>(event.wheel_y);
      break;
    case InputEvent::Kind::kKey:
      if (event.key >= 0 && event.key < IM_ARRAYSIZE(io.KeysDown)) io.KeysDown[event.key] = event.pressed;
      io.KeyCtrl = (event.mods & GLFW_MOD_CONTROL) != 0;
      io.KeyShift = (event.mods & GLFW_MOD_SHIFT) != 0;
      io.KeyAlt = (event.mods & GLFW_MOD_ALT) != 0;
      io.KeySuper = (event.mods & GLFW_MOD_SUPER) != 0;
      break;
    case InputEvent::Kind::kCharacter:
      io.AddInputCharacter(event.codepoint);
      break;
    case InputEvent::Kind::kClose:
      break;
  }
}

void ImguiLayer::beginFrame(std::uint32_t width, std::uint32_t height, double delta_s) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = static_cast<float>(delta_s > 0.0 ? delta_s : 1.0 / 60.0);
  ImGui_ImplVulkan_NewFrame();
  ImGui::NewFrame();
  frame_ended_ = false;
}

bool ImguiLayer::wantsMouse() const {
  return ImGui::GetIO().WantCaptureMouse;
}

bool ImguiLayer::wantsKeyboard() const {
  return ImGui::GetIO().WantCaptureKeyboard;
}

void ImguiLayer::endFrame() {
  ImGui::Render();
  frame_ended_ = true;
}

void ImguiLayer::record(VkCommandBuffer commands, const gpu::SwapchainImage& image) {
  assert(frame_ended_ && "call endFrame() before the renderer presents");
  const Target& target = targetFor(image);
  const bool panel = image.presented_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = panel ? panel_pass_ : render_pass_;
  begin.framebuffer = target.framebuffer;
  begin.renderArea.extent = target.extent;
  vkCmdBeginRenderPass(commands, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), commands);
  vkCmdEndRenderPass(commands);
}

const ImguiLayer::Target& ImguiLayer::targetFor(const gpu::SwapchainImage& image) {
  // A rebuilt swapchain has new images (and waited for the device): the old targets go.
  if (swapchain_.rebuilds() != targets_rebuild_) {
    destroyTargets();
    targets_rebuild_ = swapchain_.rebuilds();
  }
  Target& target = targets_[image.image];
  if (target.framebuffer != VK_NULL_HANDLE) return target;
  target.view =
      gpu::createImageView(device_.handle(), image.image, image.format, VK_IMAGE_ASPECT_COLOR_BIT, "imgui target");
  VkFramebufferCreateInfo framebuffer{};
  framebuffer.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  framebuffer.renderPass = render_pass_;
  framebuffer.attachmentCount = 1;
  framebuffer.pAttachments = &target.view;
  framebuffer.width = image.extent.width;
  framebuffer.height = image.extent.height;
  framebuffer.layers = 1;
  gpu::check(vkCreateFramebuffer(device_.handle(), &framebuffer, nullptr, &target.framebuffer), "vkCreateFramebuffer");
  target.extent = image.extent;
  return target;
}

void ImguiLayer::destroyTargets() {
  for (auto& [image, target] : targets_) {
    vkDestroyFramebuffer(device_.handle(), target.framebuffer, nullptr);
    vkDestroyImageView(device_.handle(), target.view, nullptr);
  }
  targets_.clear();
}

}  // namespace plumb::viewer
