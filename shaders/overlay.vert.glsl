#version 460
// Overlays (translucent polygons, edge lines, corner and snap markers, the growing outline):
// vertices pulled from a buffer address, lines and markers widened on screen to their pixel
// sizes, the view depth passed on for the fragment shader's test against the cloud.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "project_point.glsl"
#include "render_layout.h"

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Vertices { OverlayVertex vertex[]; };

layout(push_constant) uniform Push { OverlayPush push; };

layout(location = 0) out vec4 colour;
layout(location = 1) out float view_depth;
layout(location = 2) flat out uint flags;

void main() {
  const OverlayVertex v = Vertices(push.vertices).vertex[gl_VertexIndex];
  const vec3 position = vec3(v.position[0], v.position[1], v.position[2]);
  const mat4 clip_from_eye = matrixOf(push.clip_from_eye);
  vec4 clip = clip_from_eye * vec4(position, 1.0);
  const vec2 pixels_to_ndc = 2.0 / vec2(push.width, push.height);
  if ((v.flags & kOverlayLine) != 0u) {
    const vec4 other = clip_from_eye * vec4(v.other[0], v.other[1], v.other[2], 1.0);
    // The line's direction in pixels; its normal pushes this vertex sideways.
    vec2 along = (other.xy / max(other.w, 1e-6) - clip.xy / max(clip.w, 1e-6)) / pixels_to_ndc;
    along = length(along) > 1e-6 ? normalize(along) : vec2(1.0, 0.0);
    clip.xy += vec2(-along.y, along.x) * v.offset_px[0] * pixels_to_ndc * clip.w;
  } else if ((v.flags & kOverlayMarker) != 0u) {
    clip.xy += vec2(v.offset_px[0], v.offset_px[1]) * pixels_to_ndc * clip.w;
  }
  gl_Position = clip;
  colour = unpackUnorm4x8(v.colour);
  view_depth = dot(vec4(push.depth_from_eye[0], push.depth_from_eye[1], push.depth_from_eye[2], push.depth_from_eye[3]),
                   vec4(position, 1.0));
  flags = v.flags;
}
