#pragma once
// RGBA8 images and PNG files (stb_image_write and stb_image, Debian's libstb). Renders are
// written with writePng and read back by the tests with readPng.

#include <cstdint>
#include <string>
#include <vector>

namespace plumb::io {

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // rows top to bottom, 4 bytes per pixel

  std::uint32_t pixel(int x, int y) const {  // R in the lowest byte
    const std::size_t i =
        4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
    return std::uint32_t{rgba[i]} | std::uint32_t{rgba[i + 1]} << 8 | std::uint32_t{rgba[i + 2]} << 16 |
           std::uint32_t{rgba[i + 3]} << 24;
  }
};

// Writes `image` as a PNG atomically (AtomicFile: nothing appears at `path` on failure).
// Throws plumb::Error naming the path.
void writePng(const RgbaImage& image, const std::string& path);

// Reads a PNG as RGBA8. Throws plumb::Error naming the path for a missing or broken file.
RgbaImage readPng(const std::string& path);

}  // namespace plumb::io
