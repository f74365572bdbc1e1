#pragma once
// The depth pass: a frame's view depths into a depth image the caller owns (a headset eye's,
// which its runtime uses to reproject: XR_KHR_composition_layer_depth), by one full-screen
// triangle whose fragment shader reads the resolved visibility (shaders/depth_out.*.glsl).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <memory>

#include "engine/gpu/graphics_pipeline.h"

namespace plumb::gpu {
class DeletionQueue;
class Device;
}  // namespace plumb::gpu
namespace plumb::view {
struct Camera;
}

namespace plumb::render {

struct RenderTarget;

class DepthOutPass {
 public:
  explicit DepthOutPass(const gpu::Device& device);
  ~DepthOutPass();
  DepthOutPass(const DepthOutPass&) = delete;
  DepthOutPass& operator=(const DepthOutPass&) = delete;

  // Records the pass: `image` (`format`: D32_SFLOAT or D16_UNORM, the target's size, content not
  // needed) gets the camera's projection of each pixel's depth and is left in `final_layout`.
  // The target's resolved buffer must be written (compute) before. The image view it makes is
  // destroyed once the frame `frame_value` is done (`deletions`).
  void record(VkCommandBuffer commands, const RenderTarget& target, const view::Camera& camera, VkImage image,
              VkFormat format, VkImageLayout final_layout, gpu::DeletionQueue& deletions, std::uint64_t frame_value);

 private:
  const gpu::Device& device_;
  std::map<VkFormat, std::unique_ptr<gpu::GraphicsPipeline>> pipelines_;  // made at a format's first use
};

}  // namespace plumb::render
