#version 460
// The splat (Schuetz et al. 2021, "Rendering point clouds with compute shaders"): one work group
// per chunk of a node's points; each point is projected and kept per pixel by a 64-bit atomicMin
// of (view depth << 32 | point id), so the nearest point wins whatever order the GPU runs in,
// and ties go to the lower id (ids: render_layout.h). Depths are positive floats, whose bits order like integers.
// Points the clip region (ClipPlanes) cuts away are skipped: not drawn, so never picked.
// Each point then covers a disc in the plane of its surface (a surfel, engine/render/surfels.h)
// of the drawn cloud's spacing around it, at the plane's depth in each pixel: surfaces close at
// any distance, and where discs of one surface overlap their depths agree but for noise. Or,
// for the comparison, a square facing the eye (Potree's adaptive point size), or its pixel alone
// (splat_footprint.glsl). A footprint of more than kMaxDirectSplatWork pixels is listed for the
// wide pass (splat_wide.comp.glsl), which shares its rows out among a work group.
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "project_point.glsl"
#include "render_layout.h"

layout(local_size_x = kSplatGroupSize) in;

layout(buffer_reference, std430, buffer_reference_align = 8) buffer Wide { WideSplatHeader header; uvec2 block[]; };

layout(push_constant) uniform Push { SplatPush push; };

#include "splat_footprint.glsl"

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
  if (push.shape == kSplatPoint || chunk.discs == 0u) {
    // Every point one pixel (the benchmark's measure of the bare splat, and the chunks of nodes
    // too far for a disc to reach a pixel's radius): without the footprints' work.
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
  // Each point its pixel and its disc or square: here where small, else by the wide pass.
  for (uint i = gl_LocalInvocationID.x; i < chunk.point_count; i += kSplatGroupSize) {
    Footprint f;
    if (!footprintOf(i, first_id | i, chunk, clip_from_node, depth_row, push.shape, size, f)) continue;
    if (all(greaterThanEqual(f.centre, vec2(0.0))) && all(lessThan(f.centre, vec2(size)))) {
      const uvec2 pixel = uvec2(f.centre);
      atomicMin(visibility.pixel[pixel.y * push.width + pixel.x], f.value);
    }
    const uint rows = uint(max(f.rows.y - f.rows.x, 0)), columns = uint(max(f.columns.y - f.columns.x, 0));
    if (f.shape == kSplatPoint || rows == 0u || columns == 0u) continue;
    if (rows * (columns + 1u) <= kMaxDirectSplatWork) {
      coverRows(f, visibility, push.width, 0, 1);
      continue;
    }
    const uint blocks = (rows + kWideSplatGroupSize - 1u) / kWideSplatGroupSize;
    Wide wide = Wide(push.wide);
    const uint first_block = atomicAdd(wide.header.claimed, blocks);
    // Where the list is full (far beyond any real frame: each block needs a footprint of more
    // than 1,024 pixels), the splat covers it itself.
    if (first_block + blocks > push.wide_capacity) {
      coverRows(f, visibility, push.width, 0, 1);
      continue;
    }
    for (uint b = 0u; b < blocks; ++b) {
      const uint first_row = uint(f.rows.x) + b * kWideSplatGroupSize;
      const uint block_rows = min(uint(f.rows.y) - first_row, kWideSplatGroupSize);
      wide.block[first_block + b] = uvec2(first_id | i, first_row | block_rows << 16);
    }
    // Every block below `listed` is written: a claim that ran past the capacity was the last.
    const uint end = first_block + blocks;
    atomicMax(wide.header.listed, end);
    atomicMax(wide.header.groups[0], min(end, kWideSplatGroupsX));
    atomicMax(wide.header.groups[1], (end - 1u) / kWideSplatGroupsX + 1u);
  }
}
