#include "engine/io/png_image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstddef>
#include <memory>

#include "engine/core/atomic_file.h"
#include "engine/core/error.h"

namespace plumb::io {

void writePng(const RgbaImage& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != 4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    throw fileError(path, "an image of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                              " pixels with " + std::to_string(image.rgba.size()) + " bytes cannot be written");
  }
  std::vector<std::byte> png;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::byte>*>(context);
    out->insert(out->end(), static_cast<const std::byte*>(data), static_cast<const std::byte*>(data) + size);
  };
  if (stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0) {
    throw fileError(path, "PNG encoding failed");
  }
  AtomicFile file(path);
  file.write(png);
  file.commit();
}

RgbaImage readPng(const std::string& path) {
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<unsigned char, decltype(&stbi_image_free)> pixels(
      stbi_load(path.c_str(), &width, &height, &channels, 4), &stbi_image_free);
  if (!pixels) throw fileError(path, std::string("cannot read the PNG: ") + stbi_failure_reason());
  RgbaImage image{width, height, {}};
  image.rgba.assign(pixels.get(),
                    pixels.get() + 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  return image;
}

}  // namespace plumb::io
