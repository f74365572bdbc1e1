// What a point of the splat covers (splat.comp.glsl, splat_wide.comp.glsl): its own pixel and,
// beyond it, a disc in the plane of its surface (a surfel, engine/render/surfels.h) of the drawn
// cloud's spacing around it, at the plane's depth in each pixel, or a square facing the eye at
// the point's depth (Potree's adaptive point size). A footprint is covered row by row, and its
// rows may be shared out among the invocations of a work group (coverRows).
//
// Needs GL_EXT_shader_atomic_int64, GL_EXT_shader_explicit_arithmetic_types_int64,
// GL_EXT_buffer_reference, and render_layout.h and project_point.glsl included first.
#ifndef PLUMB_SHADERS_SPLAT_FOOTPRINT_GLSL
#define PLUMB_SHADERS_SPLAT_FOOTPRINT_GLSL

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Chunks { SplatChunk chunk[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Points { uint word[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Visibility { uint64_t pixel[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Clip { ClipPlanes region; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Surfels { uint word[]; };

// Discs under this radius on screen are their point's pixel alone: the resolve fills the
// one-pixel holes left between such points, and most points of a frame are such.
const float kMinDiscPx = 1.0;

// A point's disc on screen, cast exactly: the homography from pixel offsets from its centre to
// the disc's plane (plane_from_offset * (dx, dy, 1) = (u, v, 1) * w, the disc where
// u^2 + v^2 <= 1) and the plane's depth, linear in (u, v). Offsets from the centre, not pixel
// coordinates, keep the quadratics below well inside float precision.
struct Disc {
  mat3 plane_from_offset;
  float depth;       // at the disc's centre
  vec2 depth_slope;  // per unit of u and v
};

// A point as the splat draws it: its own pixel (`value` at `centre`, where that lies on screen)
// and what it covers beyond it, shape kSplatPoint for nothing.
struct Footprint {
  vec2 centre;     // pixels
  uint64_t value;  // view depth bits << 32 | id, at the point itself (and over all its square)
  uint shape;      // kSplatPoint, kSplatSquare or kSplatSurfel
  ivec2 rows;      // the first and one past the last row it covers, on screen
  ivec2 columns;   // likewise its columns (the disc's bounding ones)
  Disc disc;       // kSplatSurfel
};

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

// The span between the two tangents of an ellipse along one screen axis, through its dual conic:
// `along` the homography's row for that axis (offsets from the centre), `hw` its w row.
// Clamped as floats to [0, limit): a disc beside the eye projects far off screen.
ivec2 tangentSpan(const vec3 along, const vec3 hw, const float centre, const float limit) {
  const float daa = along.x * along.x + along.y * along.y;
  const float daw = along.x * hw.x + along.y * hw.y;
  const float dww = hw.x * hw.x + hw.y * hw.y - 1.0;
  const float root = sqrt(max(daw * daw - daa * dww, 0.0));
  const vec2 extent = centre + vec2((daw + root) / dww, (daw - root) / dww);
  return ivec2(clamp(vec2(floor(min(extent.x, extent.y)), floor(max(extent.x, extent.y)) + 1.0), 0.0, limit));
}

// Point i of its chunk (`id` in the visibility buffer): false where it is not drawn at all (the
// clip region cuts it away, or it lies behind the near plane); else its footprint.
bool footprintOf(const uint i, const uint id, const SplatChunk chunk, const mat4 clip_from_node, const vec4 depth_row,
                 const uint shape, const uvec2 size, out Footprint f) {
  const vec3 position = PLUMB_POINT_POSITION(Points(chunk.points).word, i * kPointWords);
  const vec3 clip_offset = vec3(chunk.clip_offset[0], chunk.clip_offset[1], chunk.clip_offset[2]);
  if (push.clip != 0 && !kept(Clip(push.clip), position + clip_offset)) return false;
  const float depth = dot(depth_row, vec4(position, 1.0));
  if (!(depth >= push.near_m)) return false;  // behind the near plane (or NaN)
  // Off screen, a point's disc may still reach into it.
  const vec4 c0 = clip_from_node * vec4(position, 1.0);
  f.centre = c0.xy / c0.w;
  f.value = (uint64_t(floatBitsToUint(depth)) << 32) | uint64_t(id);
  f.shape = kSplatPoint;
  if (shape == kSplatPoint || chunk.discs == 0u) return true;

  Surfels surfels = Surfels(chunk.surfels);
  const bvec3 upper = greaterThanEqual(position, vec3(chunk.half_cell_m));
  const uint octant = uint(upper.x) | (uint(upper.y) << 1) | (uint(upper.z) << 2);
  const float radius_m = uintBitsToFloat(surfels.word[i * kSurfelWords + 1]) * chunk.octant_scale[octant];
  // Its disc's radius on screen, were it facing the eye.
  const float radius_px = radius_m * push.pixels_per_metre / (push.perspective != 0u ? depth : 1.0);
  if (!(radius_px >= kMinDiscPx)) return true;
  if (shape == kSplatSquare) {
    const float half_side = min(radius_px, float(kMaxSplatHalfPx));
    const vec2 low = clamp(floor(f.centre - half_side), vec2(0.0), vec2(size));
    const vec2 high = clamp(floor(f.centre + half_side) + 1.0, vec2(0.0), vec2(size));
    f.shape = kSplatSquare;
    f.rows = ivec2(low.y, high.y);
    f.columns = ivec2(low.x, high.x);
    return true;
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
  const vec3 hx = vec3(eu.x - f.centre.x * eu.w, ev.x - f.centre.x * ev.w, 0.0) / c0.w;
  const vec3 hy = vec3(eu.y - f.centre.y * eu.w, ev.y - f.centre.y * ev.w, 0.0) / c0.w;
  const vec3 hw = vec3(eu.w, ev.w, c0.w) / c0.w;
  // No ellipse where the disc's plane passes through the eye or it is seen edge on: the tangents
  // to the dual conic offset_from_plane * diag(1, 1, -1) * transpose(offset_from_plane) along
  // either axis, lines (0, 1, -dy) and (1, 0, -dx), need a negative w term and real roots.
  const float dww = hw.x * hw.x + hw.y * hw.y - 1.0;
  const float dyw = hy.x * hw.x + hy.y * hw.y;
  if (!(dww < 0.0) || !(dyw * dyw - (hy.x * hy.x + hy.y * hy.y) * dww >= 0.0)) return true;
  f.shape = kSplatSurfel;
  f.rows = tangentSpan(hy, hw, f.centre.y, float(size.y));
  f.columns = tangentSpan(hx, hw, f.centre.x, float(size.x));
  f.disc = Disc(inverse(transpose(mat3(hx, hy, hw))), depth,
                disc_radius_m * vec2(dot(depth_row.xyz, t1), dot(depth_row.xyz, t2)));
  return true;
}

// Covers rows first, first + step, ... of the footprint: per row of a disc, the span of pixels
// whose centres lie inside it (where u'^2 + v'^2 - w'^2 <= 0, a quadratic along the row), each
// at the plane's depth; per row of a square, its columns at the point's depth.
void coverRows(const Footprint f, const Visibility visibility, const uint width, const int first, const int step) {
  if (f.shape == kSplatSquare) {
    for (int y = f.rows.x + first; y < f.rows.y; y += step) {
      for (int x = f.columns.x; x < f.columns.y; ++x) atomicMin(visibility.pixel[uint(y) * width + uint(x)], f.value);
    }
    return;
  }
  const Disc d = f.disc;
  // Rows of the homography: u', v', w' as dot products with (dx, dy, 1).
  const vec3 gu = vec3(d.plane_from_offset[0][0], d.plane_from_offset[1][0], d.plane_from_offset[2][0]);
  const vec3 gv = vec3(d.plane_from_offset[0][1], d.plane_from_offset[1][1], d.plane_from_offset[2][1]);
  const vec3 gw = vec3(d.plane_from_offset[0][2], d.plane_from_offset[1][2], d.plane_from_offset[2][2]);
  const float a = gu.x * gu.x + gv.x * gv.x - gw.x * gw.x;
  if (!(a > 0.0)) return;  // not an ellipse on screen
  const uint id = uint(f.value);
  for (int y = f.rows.x + first; y < f.rows.y; y += step) {
    const float dy = float(y) + 0.5 - f.centre.y;
    const float bu = gu.y * dy + gu.z, bv = gv.y * dy + gv.z, bw = gw.y * dy + gw.z;
    const float b = gu.x * bu + gv.x * bv - gw.x * bw;  // half the linear coefficient
    const float c = bu * bu + bv * bv - bw * bw;
    const float discriminant = b * b - a * c;
    if (!(discriminant >= 0.0)) continue;
    const float root = sqrt(discriminant);
    // Pixel centres x + 0.5 at offsets between the roots.
    const float low = clamp(ceil(f.centre.x + (-b - root) / a - 0.5), 0.0, float(width));
    const float high = clamp(floor(f.centre.x + (-b + root) / a - 0.5) + 1.0, 0.0, float(width));
    for (int x = int(low); x < int(high); ++x) {
      const vec3 uvw = d.plane_from_offset * vec3(float(x) + 0.5 - f.centre.x, dy, 1.0);
      const float pixel_depth = d.depth + dot(d.depth_slope, uvw.xy / uvw.z);
      atomicMin(visibility.pixel[uint(y) * width + uint(x)], (uint64_t(floatBitsToUint(pixel_depth)) << 32) | uint64_t(id));
    }
  }
}

#endif
