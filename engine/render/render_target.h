#pragma once
// What a frame renders into, for one viewport size: the splat's visibility buffer, the resolved
// buffer (holes filled; picking and overlays read it) and the RGBA8 colour, one entry per pixel,
// rows top to bottom. All device-local; the renderer copies out what the host needs.

#include <cstdint>

#include "engine/gpu/buffer.h"

namespace plumb::render {

struct RenderTarget {
  RenderTarget(const gpu::Device& device, gpu::MemoryAllocator& allocator, std::uint32_t width, std::uint32_t height);

  std::uint32_t width, height;
  gpu::Buffer visibility;  // uint64_t: depth bits << 32 | point id; all ones where empty
  gpu::Buffer resolved;    // the same after the resolve's hole filling
  gpu::Buffer colour;      // RGBA8, R in the lowest byte

  std::uint64_t pixels() const { return std::uint64_t{width} * height; }
};

}  // namespace plumb::render
