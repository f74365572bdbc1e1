// Projection helpers of the splat (splat.comp.glsl, bare_splat.comp.glsl) and the overlays. projectPoint:
// whether the point (relative to its origin) lands on a pixel in front of the near plane, that
// pixel, and its visibility value there (view depth bits << 32 | id). Needs GL_EXT_shader_explicit_arithmetic_types_int64.
#ifndef PLUMB_SHADERS_PROJECT_POINT_GLSL
#define PLUMB_SHADERS_PROJECT_POINT_GLSL

bool projectPoint(const mat4 clip_from_origin, const vec4 depth_row, const vec3 position, const uvec2 size,
                  const float near_m, const uint id, out uvec2 pixel_at, out uint64_t value) {
  const vec4 p = vec4(position, 1.0);
  const float depth = dot(depth_row, p);
  if (!(depth >= near_m)) return false;  // behind the near plane (or NaN)
  const vec4 clip = clip_from_origin * p;
  const vec2 pixel = clip.xy / clip.w;
  if (!(all(greaterThanEqual(pixel, vec2(0.0))) && all(lessThan(pixel, vec2(size))))) return false;
  pixel_at = uvec2(pixel);
  value = (uint64_t(floatBitsToUint(depth)) << 32) | uint64_t(id);
  return true;
}

// A point's position from its words (kPointWords per point).
#define PLUMB_POINT_POSITION(words, w) \
  vec3(uintBitsToFloat(words[w]), uintBitsToFloat(words[(w) + 1]), uintBitsToFloat(words[(w) + 2]))

mat4 matrixOf(const float c[16]) {
  return mat4(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10], c[11], c[12], c[13], c[14], c[15]);
}

#endif
