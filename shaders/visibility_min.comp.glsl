#version 460
// The heart of the splat (Schuetz et al. 2021): each sample keeps, per pixel, the smallest
// (depth << 32 | id) by a 64-bit atomicMin, so the nearest point wins and ties go to the lower
// id, whatever the order the GPU runs the samples in. Here the samples come projected already
// (pixel, depth); splat.comp.glsl does the projection in front of the same atomicMin.
// Depths are non-negative floats, whose bits order like unsigned integers.
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require

layout(local_size_x = 64) in;

struct Sample {
  uint pixel;
  float depth;
};

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Samples { Sample sample_at[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Visibility { uint64_t pixel[]; };

layout(push_constant) uniform Push {
  Samples samples;
  Visibility visibility;
  uint sample_count;
};

void main() {
  const uint id = gl_GlobalInvocationID.x;
  if (id >= sample_count) return;
  const Sample s = samples.sample_at[id];
  atomicMin(visibility.pixel[s.pixel], (uint64_t(floatBitsToUint(s.depth)) << 32) | uint64_t(id));
}
