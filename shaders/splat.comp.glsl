#version 460
// The splat (Schuetz et al. 2021, "Rendering point clouds with compute shaders"): one work group
// per chunk of a node's points; each point is projected and kept per pixel by a 64-bit atomicMin
// of (view depth << 32 | point id), so the nearest point wins whatever order the GPU runs in,
// and ties go to the lower id (ids: render_layout.h). Depths are positive floats, whose bits order like integers.
// Points the clip region (ClipPlanes) cuts away are skipped: not drawn, so never picked.
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
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Clip { ClipPlanes region; };

layout(push_constant) uniform Push { SplatPush push; };

// Whether the clip region keeps a point at `p` (relative to the region's anchor).
bool kept(const Clip clip, const vec3 p) {
  bool inside_box = true;
  for (uint i = 0; i < clip.region.plane_count; ++i) {
    const vec4 plane = vec4(clip.region.planes[4 * i], clip.region.planes[4 * i + 1], clip.region.planes[4 * i + 2],
                            clip.region.planes[4 * i + 3]);
    const bool on_kept_side = dot(plane.xyz, p) + plane.w >= 0.0;
    if (i < clip.region.box_planes) {
      inside_box = inside_box && on_kept_side;
    } else if (!on_kept_side) {
      return false;
    }
  }
  return clip.region.box_planes == 0u || inside_box != (clip.region.keep_outside_box != 0u);
}

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
  const bool clipped = push.clip != 0;
  const vec3 clip_offset = vec3(chunk.clip_offset[0], chunk.clip_offset[1], chunk.clip_offset[2]);
  if (chunk.point_size_px <= 1u) {
    // Apart from the finest nodes close up, every chunk: kept tight, without the square's loop.
    for (uint i = gl_LocalInvocationID.x; i < chunk.point_count; i += kSplatGroupSize) {
      uvec2 pixel;
      uint64_t value;
      const vec3 position = PLUMB_POINT_POSITION(points.word, i * kPointWords);
      if (clipped && !kept(Clip(push.clip), position + clip_offset)) continue;
      if (projectPoint(clip_from_node, depth_row, position, size, push.near_m, first_id | i, pixel, value)) {
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
    const vec3 position = PLUMB_POINT_POSITION(points.word, i * kPointWords);
    if (clipped && !kept(Clip(push.clip), position + clip_offset)) continue;
    if (!projectPoint(clip_from_node, depth_row, position, size, push.near_m, first_id | i, pixel, value)) continue;
    const uvec2 low = uvec2(max(ivec2(pixel) - int(side / 2u), ivec2(0)));
    const uvec2 high = min(low + side, size);
    for (uint y = low.y; y < high.y; ++y) {
      for (uint x = low.x; x < high.x; ++x) atomicMin(visibility.pixel[y * push.width + x], value);
    }
  }
}
