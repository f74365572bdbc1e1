#version 460
// Overlays are depth-tested against the cloud: a fragment further than the splat's point at its
// pixel (beyond a tolerance, so that a polygon on a noisy wall still shows) is hidden, unless
// it is drawn on top (snap markers).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "render_layout.h"

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Resolved { uint64_t pixel[]; };

layout(push_constant) uniform Push { OverlayPush push; };

layout(location = 0) in vec4 colour;
layout(location = 1) in float view_depth;
layout(location = 2) flat in uint flags;

layout(location = 0) out vec4 result;

void main() {
  if ((flags & kOverlayOnTop) == 0u) {
    const uvec2 pixel = uvec2(gl_FragCoord.xy);
    const uint64_t value = Resolved(push.resolved).pixel[pixel.y * push.width + pixel.x];
    if (uint(value >> 32) != kEmptyHigh) {
      const float cloud_depth = uintBitsToFloat(uint(value >> 32));
      if (view_depth > cloud_depth * (1.0 + push.depth_tolerance) + 0.01) discard;
    }
  }
  result = colour;
}
