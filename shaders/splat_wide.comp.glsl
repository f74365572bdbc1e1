#version 460
// The splat's wide pass: the discs and squares too wide for one invocation of the splat
// (splat.comp.glsl), which listed them in blocks of kWideSplatGroupSize rows. One work group per
// block, an invocation per row: the point's footprint again (splat_footprint.glsl), each pixel
// kept by the same 64-bit atomicMin, so the picture is the same whichever pass covers a pixel.
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "project_point.glsl"
#include "render_layout.h"

layout(local_size_x = kWideSplatGroupSize) in;

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Wide {
  WideSplatHeader header;
  uvec2 block[];
};

layout(push_constant) uniform Push { SplatPush push; };

#include "splat_footprint.glsl"

void main() {
  Wide wide = Wide(push.wide);
  const uint n = gl_WorkGroupID.y * kWideSplatGroupsX + gl_WorkGroupID.x;
  if (n >= wide.header.listed) return;  // the grid's last row reaches past the list
  const uvec2 block = wide.block[n];
  // The block's first row (low 16 bits) and its rows (high 16): an invocation past them is done.
  const uint first_row = block.y & 0xFFFFu;
  if (gl_LocalInvocationID.x >= block.y >> 16) return;
  const uint id = block.x;
  const SplatChunk chunk = Chunks(push.chunks).chunk[id >> kChunkBits];
  const vec4 depth_row = vec4(chunk.depth_from_node[0], chunk.depth_from_node[1], chunk.depth_from_node[2],
                              chunk.depth_from_node[3]);
  Footprint f;
  if (!footprintOf(id & (kChunkPoints - 1u), id, chunk, matrixOf(chunk.clip_from_node), depth_row, push.shape,
                   uvec2(push.width, push.height), f)) {
    return;
  }
  // This invocation's row of the block.
  f.rows = ivec2(int(first_row + gl_LocalInvocationID.x), int(first_row + gl_LocalInvocationID.x) + 1);
  coverRows(f, Visibility(push.visibility), push.width, 0, 1);
}
