#version 460
// The splat at its barest, for the benchmark to measure the renderer's splat against: the same
// projection and 64-bit atomicMin, on one flat array of points with one transform, one
// invocation per point, no chunk table.
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "project_point.glsl"
#include "render_layout.h"

layout(local_size_x = kSplatGroupSize) in;

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Points { uint word[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Visibility { uint64_t pixel[]; };

layout(push_constant) uniform Push { BareSplatPush push; };

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= push.point_count) return;
  const vec4 depth_row = vec4(push.depth_from_points[0], push.depth_from_points[1], push.depth_from_points[2],
                              push.depth_from_points[3]);
  Points points = Points(push.points);
  uvec2 pixel;
  uint64_t value;
  if (projectPoint(matrixOf(push.clip_from_points), depth_row, PLUMB_POINT_POSITION(points.word, i * kPointWords),
                   uvec2(push.width, push.height), push.near_m, i, pixel, value)) {
    atomicMin(Visibility(push.visibility).pixel[pixel.y * push.width + pixel.x], value);
  }
}
