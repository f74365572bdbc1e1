#pragma once
// The palette of segment labels and scans, as shaders/resolve.comp.glsl draws them, for what the
// host shows beside the picture (a legend of scans). Label 0 is "none" (grey); scan i is label
// i + 1. Hues lie a golden angle apart, so that neighbouring labels differ most.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace plumb::render {

// RGB on 0..1, the shader's segmentColour().
inline std::array<float, 3> labelColour(std::uint32_t label) {
  if (label == 0) return {0.55f, 0.55f, 0.55f};
  const float product = static_cast<float>(label) * 0.618034f;
  const float hue = product - std::floor(product);
  const std::array<float, 3> k{0.0f, 2.0f / 3.0f, 1.0f / 3.0f};
  std::array<float, 3> rgb{};
  for (std::size_t c = 0; c < 3; ++c) {
    const float shifted = hue + k[c];
    const float p = std::abs((shifted - std::floor(shifted)) * 6.0f - 3.0f) - 1.0f;
    rgb[c] = 0.25f + 0.7f * std::clamp(p, 0.0f, 1.0f);
  }
  return rgb;
}

inline std::array<float, 3> scanColour(std::uint32_t scan) {
  return labelColour(scan + 1);
}

}  // namespace plumb::render
