#version 460
// The heart of the splat (Schuetz et al. 2021): each sample keeps, per pixel, the smallest
// (depth << 32 | id) by a 64-bit atomicMin, so the nearest point wins and ties go to the lower
// id, whatever the order the GPU runs the samples in. Here the samples come projected already
// (pixel, depth); the renderer's splat does the projection in front of the same atomicMin.
// Depths are non-negative floats, whose bits order like unsigned integers.
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

struct Sample {
  uint pixel;
  float depth;
};

layout(std430, set = 0, binding = 0) readonly buffer Samples { Sample samples[]; };
layout(std430, set = 0, binding = 1) buffer Visibility { uint64_t visibility[]; };

layout(push_constant) uniform Push { uint sample_count; };

void main() {
  const uint id = gl_GlobalInvocationID.x;
  if (id >= sample_count) return;
  const Sample s = samples[id];
  atomicMin(visibility[s.pixel], (uint64_t(floatBitsToUint(s.depth)) << 32) | uint64_t(id));
}
