#pragma once
// The overlay pass: after the resolve, the colour goes into an image, the overlay scene is drawn
// over it (alpha-blended, depth-tested against the cloud in the fragment shader) and the result
// comes back into the colour buffer, which readback and presentation read.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>

#include "engine/gpu/buffer.h"
#include "engine/gpu/graphics_pipeline.h"

namespace plumb::view {
struct Camera;
}

namespace plumb::render {

struct OverlayScene;
struct RenderTarget;

class OverlayPass {
 public:
  static constexpr std::size_t kSlots = 2;  // one vertex buffer per frame in flight

  OverlayPass(const gpu::Device& device, gpu::MemoryAllocator& allocator);

  // Records the pass into `commands` for frame slot `slot` (whose previous frame is done). The
  // target's colour and resolved buffers must be written (compute) before. Returns whether it
  // drew anything: then the colour image holds the result too, in TRANSFER_SRC_OPTIMAL.
  bool record(VkCommandBuffer commands, std::size_t slot, const RenderTarget& target, const OverlayScene& scene,
              const view::Camera& camera, float depth_tolerance);

 private:
  const gpu::Device& device_;
  gpu::MemoryAllocator& allocator_;
  gpu::GraphicsPipeline pipeline_;
  std::array<gpu::Buffer, kSlots> vertices_;  // host-visible
};

}  // namespace plumb::render
