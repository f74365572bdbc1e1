#version 460
// The depth pass: each pixel's view depth, from the resolved visibility (depth bits << 32 |
// point id, all ones where empty), as the standard Vulkan perspective projection maps it:
// far (d - near) / (d (far - near)), 0 at the near plane, 1 at the far one and where nothing
// was drawn.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "render_layout.h"

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Visibility { uint64_t pixel[]; };

layout(push_constant) uniform Push { DepthOutPush push; };

void main() {
  const uvec2 p = uvec2(gl_FragCoord.xy);
  const uint64_t value = Visibility(push.resolved).pixel[p.y * push.width + p.x];
  const uint bits = uint(value >> 32);
  if (bits == kEmptyHigh) {
    gl_FragDepth = 1.0;
    return;
  }
  const float d = max(uintBitsToFloat(bits), push.near_m);
  gl_FragDepth = clamp(push.far_m * (d - push.near_m) / (d * (push.far_m - push.near_m)), 0.0, 1.0);
}
