#pragma once
// A graphics pipeline for dynamic rendering into one colour attachment (alpha-blended) or one
// depth attachment (written whatever was there: a depth the fragment shader computes), drawing
// vertices the vertex shader pulls itself from a buffer address in the push constants (no vertex
// input state, no descriptor sets), with the viewport and scissor set per draw.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>

namespace plumb::gpu {

class Device;

class GraphicsPipeline {
 public:
  // `push_bytes`: the push constant block both stages share. Triangle lists, no culling. A
  // `depth_format` makes a depth-only pipeline (then `colour_format` must be UNDEFINED).
  GraphicsPipeline(const Device& device, std::span<const std::uint32_t> vertex_spirv,
                   std::span<const std::uint32_t> fragment_spirv, std::uint32_t push_bytes, VkFormat colour_format,
                   const char* name, VkFormat depth_format = VK_FORMAT_UNDEFINED);
  ~GraphicsPipeline();
  GraphicsPipeline(const GraphicsPipeline&) = delete;
  GraphicsPipeline& operator=(const GraphicsPipeline&) = delete;

  // Inside vkCmdBeginRendering: binds, sets the viewport and scissor to `width` x `height`,
  // pushes `push` and draws `vertex_count` vertices.
  template <typename Push>
  void draw(VkCommandBuffer commands, const Push& push, std::uint32_t vertex_count, std::uint32_t width,
            std::uint32_t height) const {
    static_assert(sizeof(Push) <= 128, "push constants beyond the guaranteed 128 bytes");
    drawRaw(commands, &push, sizeof(Push), vertex_count, width, height);
  }

 private:
  void drawRaw(VkCommandBuffer commands, const void* push, std::uint32_t bytes, std::uint32_t vertex_count,
               std::uint32_t width, std::uint32_t height) const;

  VkDevice device_;
  std::uint32_t push_bytes_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace plumb::gpu
