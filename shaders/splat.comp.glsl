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
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Surfels { uint word[]; };

// A unit normal from its octahedral encoding (engine/render/surfels.cpp's encodeNormal).
vec3 decodeNormal(const uint packed) {
  const vec2 e = max(vec2(float(int(packed << 16) >> 16), float(int(packed) >> 16)) / 32767.0, vec2(-1.0));
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

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
  if (push.shape == kSplatPoint) {
    // Every point one pixel (the benchmark's measure of the bare splat): without the discs' loop.
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
  // Each point a disc in the plane of its surface (a surfel), as the affine map of the disc to the
  // screen: pixel offsets from the point's projection back to the disc's (u, v), covered where
  // u^2 + v^2 <= 1, at the depth of the disc's plane there. Its own pixel always.
  Surfels surfels = Surfels(chunk.surfels);
  for (uint i = gl_LocalInvocationID.x; i < chunk.point_count; i += kSplatGroupSize) {
    const vec3 position = PLUMB_POINT_POSITION(points.word, i * kPointWords);
    if (clipped && !kept(Clip(push.clip), position + clip_offset)) continue;
    const float depth = dot(depth_row, vec4(position, 1.0));
    if (!(depth >= push.near_m)) continue;  // behind the near plane (or NaN)
    // Off screen, a point's disc may still reach into it.
    const vec4 c0 = clip_from_node * vec4(position, 1.0);
    const vec2 centre = c0.xy / c0.w;
    const uint id_bits = first_id | i;
    if (all(greaterThanEqual(centre, vec2(0.0))) && all(lessThan(centre, vec2(size)))) {
      const uvec2 pixel = uvec2(centre);
      atomicMin(visibility.pixel[pixel.y * push.width + pixel.x], (uint64_t(floatBitsToUint(depth)) << 32) | id_bits);
    }

    const bvec3 upper = greaterThanEqual(position, vec3(chunk.half_cell_m));
    const uint octant = uint(upper.x) | (uint(upper.y) << 1) | (uint(upper.z) << 2);
    const float radius_m = uintBitsToFloat(surfels.word[i * kSurfelWords + 1]) * chunk.octant_scale[octant];
    if (radius_m == 0.0) continue;
    if (push.shape == kSplatSquare) {
      // A square facing the eye, flat at the point's depth (Potree's adaptive point size).
      const float half_side =
          min(radius_m * push.pixels_per_metre / (push.perspective != 0u ? depth : 1.0), float(kMaxSplatHalfPx));
      const ivec2 low = ivec2(clamp(floor(centre - half_side), vec2(0.0), vec2(size)));
      const ivec2 high = ivec2(clamp(floor(centre + half_side) + 1.0, vec2(0.0), vec2(size)));
      const uint64_t value = (uint64_t(floatBitsToUint(depth)) << 32) | uint64_t(id_bits);
      for (int y = low.y; y < high.y; ++y) {
        for (int x = low.x; x < high.x; ++x) atomicMin(visibility.pixel[uint(y) * push.width + uint(x)], value);
      }
      continue;
    }
    // The disc's axes: in its plane, or facing the eye (the view direction in node coordinates
    // is depth_row.xyz, whose length is 1: the view is a rotation and a translation).
    const uint packed = surfels.word[i * kSurfelWords];
    const vec3 normal = packed == kSurfelFacingTheEye ? depth_row.xyz : decodeNormal(packed);
    const vec3 t1 = normalize(cross(normal, abs(normal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    const vec3 t2 = cross(normal, t1);
    const vec4 c1 = clip_from_node * vec4(position + radius_m * t1, 1.0);
    const vec4 c2 = clip_from_node * vec4(position + radius_m * t2, 1.0);
    if (c1.w <= 0.0 || c2.w <= 0.0) continue;
    const mat2 screen_from_disc = mat2(c1.xy / c1.w - centre, c2.xy / c2.w - centre);
    const float det = determinant(screen_from_disc);
    if (abs(det) < 0.25) continue;  // edge-on, or under a pixel: the point's own pixel
    const mat2 disc_from_screen = inverse(screen_from_disc);
    const vec2 depth_slope = radius_m * vec2(dot(depth_row.xyz, t1), dot(depth_row.xyz, t2));
    const vec2 extent = min(vec2(length(vec2(screen_from_disc[0].x, screen_from_disc[1].x)),
                                 length(vec2(screen_from_disc[0].y, screen_from_disc[1].y))),
                            vec2(float(kMaxSplatHalfPx)));
    // Clamped as floats: a point beside the eye projects far off screen.
    const ivec2 low = ivec2(clamp(floor(centre - extent), vec2(0.0), vec2(size)));
    const ivec2 high = ivec2(clamp(floor(centre + extent) + 1.0, vec2(0.0), vec2(size)));
    for (int y = low.y; y < high.y; ++y) {
      for (int x = low.x; x < high.x; ++x) {
        const vec2 uv = disc_from_screen * (vec2(x, y) + 0.5 - centre);
        if (dot(uv, uv) > 1.0) continue;
        const float pixel_depth = depth + dot(depth_slope, uv);
        if (!(pixel_depth >= push.near_m)) continue;
        atomicMin(visibility.pixel[uint(y) * push.width + uint(x)],
                  (uint64_t(floatBitsToUint(pixel_depth)) << 32) | uint64_t(id_bits));
      }
    }
  }
}
