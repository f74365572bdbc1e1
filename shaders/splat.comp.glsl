#version 460
// The splat (Schuetz et al. 2021, "Rendering point clouds with compute shaders"): one work group
// per chunk of a node's points; each point is projected and kept per pixel by a 64-bit atomicMin
// of (view depth << 32 | point id), so the nearest point wins whatever order the GPU runs in,
// and ties go to the lower id (ids: render_layout.h). Depths are positive floats, whose bits order like integers.
// Points the clip region (ClipPlanes) cuts away are skipped: not drawn, so never picked.
// Each point then covers a disc in the plane of its surface (a surfel, engine/render/surfels.h)
// of the drawn cloud's spacing around it, at the plane's depth in each pixel: surfaces close at
// any distance, and where discs of one surface overlap their depths agree but for noise. Or,
// for the comparison, a square facing the eye (Potree's adaptive point size), or its pixel alone.
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

layout(push_constant) uniform Push { SplatPush push; };

// Discs under this radius on screen are their point's pixel alone: the resolve fills the
// one-pixel holes left between such points, and most points of a frame are such.
const float kMinDiscPx = 1.0;

// A point's disc on screen, cast exactly: the homography from pixel offsets from its centre to
// the disc's plane (plane_from_offset * (dx, dy, 1) = (u, v, 1) * w, the disc where
// u^2 + v^2 <= 1) and the plane's depth, linear in (u, v). Offsets from the centre, not pixel
// coordinates, keep the quadratics below well inside float precision.
struct Disc {
  vec2 centre;  // pixels
  mat3 plane_from_offset;
  float depth;       // at the disc's centre
  vec2 depth_slope;  // per unit of u and v
  uint id;
  ivec2 rows;  // the first and one past the last row it covers, on screen
};

// Casts the disc: per row, the span of pixels whose centres lie inside it (where
// u'^2 + v'^2 - w'^2 <= 0, a quadratic along the row), each at the plane's depth.
void castDisc(const Disc d, const Visibility visibility, const uint width) {
  // Rows of the homography: u', v', w' as dot products with (dx, dy, 1).
  const vec3 gu = vec3(d.plane_from_offset[0][0], d.plane_from_offset[1][0], d.plane_from_offset[2][0]);
  const vec3 gv = vec3(d.plane_from_offset[0][1], d.plane_from_offset[1][1], d.plane_from_offset[2][1]);
  const vec3 gw = vec3(d.plane_from_offset[0][2], d.plane_from_offset[1][2], d.plane_from_offset[2][2]);
  const float a = gu.x * gu.x + gv.x * gv.x - gw.x * gw.x;
  if (!(a > 0.0)) return;  // not an ellipse on screen
  for (int y = d.rows.x; y < d.rows.y; ++y) {
    const float dy = float(y) + 0.5 - d.centre.y;
    const float bu = gu.y * dy + gu.z, bv = gv.y * dy + gv.z, bw = gw.y * dy + gw.z;
    const float b = gu.x * bu + gv.x * bv - gw.x * bw;  // half the linear coefficient
    const float c = bu * bu + bv * bv - bw * bw;
    const float discriminant = b * b - a * c;
    if (!(discriminant >= 0.0)) continue;
    const float root = sqrt(discriminant);
    // Pixel centres x + 0.5 at offsets between the roots.
    const float low = clamp(ceil(d.centre.x + (-b - root) / a - 0.5), 0.0, float(width));
    const float high = clamp(floor(d.centre.x + (-b + root) / a - 0.5) + 1.0, 0.0, float(width));
    for (int x = int(low); x < int(high); ++x) {
      const vec3 uvw = d.plane_from_offset * vec3(float(x) + 0.5 - d.centre.x, dy, 1.0);
      const float pixel_depth = d.depth + dot(d.depth_slope, uvw.xy / uvw.z);
      atomicMin(visibility.pixel[uint(y) * width + uint(x)], (uint64_t(floatBitsToUint(pixel_depth)) << 32) | uint64_t(d.id));
    }
  }
}

// A unit normal from its octahedral encoding (engine/render/surfels.cpp's encodeNormal).
vec3 decodeNormal(const uint packed) {
  const vec2 e = max(vec2(float(int(packed << 16) >> 16), float(int(packed) >> 16)) / 32767.0, vec2(-1.0));
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

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

// Point i of the chunk: drawn at its own pixel; for a square, the square too (false); for a
// surfel of a disc beyond its pixel, that disc (true).
bool surfelOf(const uint i, const SplatChunk chunk, const mat4 clip_from_node, const vec4 depth_row, const Points points,
              const Surfels surfels, const uvec2 size, out Disc disc) {
  Visibility visibility = Visibility(push.visibility);
  const vec3 position = PLUMB_POINT_POSITION(points.word, i * kPointWords);
  const vec3 clip_offset = vec3(chunk.clip_offset[0], chunk.clip_offset[1], chunk.clip_offset[2]);
  if (push.clip != 0 && !kept(Clip(push.clip), position + clip_offset)) return false;
  const float depth = dot(depth_row, vec4(position, 1.0));
  if (!(depth >= push.near_m)) return false;  // behind the near plane (or NaN)
  // Off screen, a point's disc may still reach into it.
  const vec4 c0 = clip_from_node * vec4(position, 1.0);
  const vec2 centre = c0.xy / c0.w;
  const uint id = (gl_WorkGroupID.x << kChunkBits) | i;
  const uint64_t value = (uint64_t(floatBitsToUint(depth)) << 32) | uint64_t(id);
  if (all(greaterThanEqual(centre, vec2(0.0))) && all(lessThan(centre, vec2(size)))) {
    const uvec2 pixel = uvec2(centre);
    atomicMin(visibility.pixel[pixel.y * push.width + pixel.x], value);
  }

  const bvec3 upper = greaterThanEqual(position, vec3(chunk.half_cell_m));
  const uint octant = uint(upper.x) | (uint(upper.y) << 1) | (uint(upper.z) << 2);
  const float radius_m = uintBitsToFloat(surfels.word[i * kSurfelWords + 1]) * chunk.octant_scale[octant];
  // Its disc's radius on screen, were it facing the eye.
  const float radius_px = radius_m * push.pixels_per_metre / (push.perspective != 0u ? depth : 1.0);
  if (radius_px < kMinDiscPx) return false;
  if (push.shape == kSplatSquare) {
    // A square facing the eye, flat at the point's depth (Potree's adaptive point size).
    const float half_side = min(radius_px, float(kMaxSplatHalfPx));
    const ivec2 low = ivec2(clamp(floor(centre - half_side), vec2(0.0), vec2(size)));
    const ivec2 high = ivec2(clamp(floor(centre + half_side) + 1.0, vec2(0.0), vec2(size)));
    for (int y = low.y; y < high.y; ++y) {
      for (int x = low.x; x < high.x; ++x) atomicMin(visibility.pixel[uint(y) * push.width + uint(x)], value);
    }
    return false;
  }
  // The disc's axes: in its plane, or facing the eye (the view direction in node coordinates is
  // depth_row.xyz, whose length is 1: the view is a rotation and a translation).
  const uint packed = surfels.word[i * kSurfelWords];
  const vec3 normal = packed == kSurfelFacingTheEye ? depth_row.xyz : decodeNormal(packed);
  const vec3 t1 = normalize(cross(normal, abs(normal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  const vec3 t2 = cross(normal, t1);
  // A disc reaching to the near plane would not be an ellipse on screen: near the eye, discs
  // shrink to stay in front of it (a point there covers much of the screen still).
  const float disc_radius_m = min(radius_m, 0.9 * (depth - push.near_m));
  // Pixel offsets from the centre (times w) from the disc's (u, v, 1): the clip transform's x,
  // y and w rows less the centre's share, over the centre's w (which keeps the conic).
  const vec4 eu = clip_from_node * vec4(disc_radius_m * t1, 0.0), ev = clip_from_node * vec4(disc_radius_m * t2, 0.0);
  const vec3 hx = vec3(eu.x - centre.x * eu.w, ev.x - centre.x * ev.w, 0.0) / c0.w;
  const vec3 hy = vec3(eu.y - centre.y * eu.w, ev.y - centre.y * ev.w, 0.0) / c0.w;
  const vec3 hw = vec3(eu.w, ev.w, c0.w) / c0.w;
  const mat3 offset_from_plane = transpose(mat3(hx, hy, hw));
  // The rows between the ellipse's horizontal tangents: lines (0, 1, -dy) of its dual conic
  // offset_from_plane * diag(1, 1, -1) * transpose(offset_from_plane).
  const float dyy = hy.x * hy.x + hy.y * hy.y;
  const float dyw = hy.x * hw.x + hy.y * hw.y;
  const float dww = hw.x * hw.x + hw.y * hw.y - 1.0;
  const float tangents = dyw * dyw - dyy * dww;
  if (!(dww < 0.0) || !(tangents >= 0.0)) return false;  // no ellipse (edge-on or at the eye)
  const float root = sqrt(tangents);
  const vec2 extent = centre.y + vec2((dyw + root) / dww, (dyw - root) / dww);
  // Clamped as floats: a disc beside the eye projects far off screen.
  const vec2 rows = clamp(vec2(floor(min(extent.x, extent.y)), floor(max(extent.x, extent.y)) + 1.0), 0.0, float(size.y));
  disc = Disc(centre, inverse(offset_from_plane), depth,
              disc_radius_m * vec2(dot(depth_row.xyz, t1), dot(depth_row.xyz, t2)), id, ivec2(rows));
  return disc.rows.y > disc.rows.x;
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
  if (push.shape == kSplatPoint || chunk.discs == 0u) {
    // Every point one pixel (the benchmark's measure of the bare splat, and the chunks of nodes
    // too far for a disc to reach a pixel's radius): without the discs' loop.
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
  // Each point a disc in the plane of its surface (a surfel), or a square facing the eye.
  Surfels surfels = Surfels(chunk.surfels);
  for (uint i = gl_LocalInvocationID.x; i < chunk.point_count; i += kSplatGroupSize) {
    Disc disc;
    if (surfelOf(i, chunk, clip_from_node, depth_row, points, surfels, size, disc)) castDisc(disc, visibility, push.width);
  }
}
