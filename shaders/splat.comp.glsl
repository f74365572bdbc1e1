#version 460
// The splat (Schuetz et al. 2021, "Rendering point clouds with compute shaders"): one work group
// per chunk of a node's points; each point is projected and kept per pixel by a 64-bit atomicMin
// of (view depth << 32 | point id), so the nearest point wins whatever order the GPU runs in,
// and ties go to the lower id (ids: render_layout.h). Depths are positive floats, whose bits order like integers.
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "project_point.glsl"
#include "render_layout.h"

layout(local_size_x = kSplatGroupSize) in;

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Chunks { SplatChunk chunk[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Points { uint word[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Visibility { uint64_t pixel[]; };

layout(push_constant) uniform Push { SplatPush push; };

void main() {
  const uint chunk_index = gl_WorkGroupID.x;
  const SplatChunk chunk = Chunks(push.chunks).chunk[chunk_index];
  const mat4 clip_from_node = matrixOf(chunk.clip_from_node);
  const vec4 depth_row = vec4(chunk.depth_from_node[0], chunk.depth_from_node[1], chunk.depth_from_node[2],
                              chunk.depth_from_node[3]);
  Points points = Points(chunk.points);
  Visibility visibility = Visibility(push.visibility);
  const uvec2 size = uvec2(push.width, push.height);

  const uint first_id = chunk_index << kChunkBits;
  if (chunk.point_size_px <= 1u) {
    // Apart from the finest nodes close up, every chunk: kept tight, without the square's loop.
    for (uint i = gl_LocalInvocationID.x; i < chunk.point_count; i += kSplatGroupSize) {
      uvec2 pixel;
      uint64_t value;
      if (projectPoint(clip_from_node, depth_row, PLUMB_POINT_POSITION(points.word, i * kPointWords), size,
                       push.near_m, first_id | i, pixel, value)) {
        atomicMin(visibility.pixel[pixel.y * push.width + pixel.x], value);
      }
    }
    return;
  }
  // A square around each point's pixel, clipped to the screen.
  const uint side = chunk.point_size_px;
  for (uint i = gl_LocalInvocationID.x; i < chunk.point_count; i += kSplatGroupSize) {
    uvec2 pixel;
    uint64_t value;
    if (!projectPoint(clip_from_node, depth_row, PLUMB_POINT_POSITION(points.word, i * kPointWords), size,
                      push.near_m, first_id | i, pixel, value)) {
      continue;
    }
    const uvec2 low = uvec2(max(ivec2(pixel) - int(side / 2u), ivec2(0)));
    const uvec2 high = min(low + side, size);
    for (uint y = low.y; y < high.y; ++y) {
      for (uint x = low.x; x < high.x; ++x) atomicMin(visibility.pixel[y * push.width + x], value);
    }
  }
}
