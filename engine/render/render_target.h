#pragma once
// What a frame renders into, for one viewport size: the splat's visibility buffer, the resolved
// buffer (holes filled; picking and overlays read it) and the RGBA8 colour, one entry per pixel,
// rows top to bottom, and the colour image the overlays draw into. All device-local; the
// renderer copies out what the host needs.

#include <cstdint>

#include "engine/gpu/buffer.h"
#include "engine/gpu/image.h"

namespace plumb::render {

struct RenderTarget {
  static constexpr VkFormat kColourFormat = VK_FORMAT_R8G8B8A8_UNORM;  // the colour buffer's layout

  RenderTarget(const gpu::Device& device, gpu::MemoryAllocator& allocator, std::uint32_t width, std::uint32_t height);

  std::uint32_t width, height;
  gpu::Buffer visibility;   // uint64_t: depth bits << 32 | point id; all ones where empty
  gpu::Buffer resolved;     // the same after the resolve's hole filling
  gpu::Buffer colour;       // RGBA8, R in the lowest byte
  gpu::Image colour_image;  // the colour as an image: overlays draw into it, presentation blits it

  std::uint64_t pixels() const { return std::uint64_t{width} * height; }

  // The whole colour image as one copy region, to and from the colour buffer.
  VkBufferImageCopy colourRegion() const;
  // Records the copy of the colour buffer (written by the resolve) into the colour image, left
  // in `layout` for `next_stages` to access by `next_access`.
  void copyColourToImage(VkCommandBuffer commands, VkImageLayout layout, VkPipelineStageFlags2 next_stages,
                         VkAccessFlags2 next_access) const;
};

}  // namespace plumb::render
