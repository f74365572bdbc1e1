#version 460
// The resolve: from the visibility buffer to colour. Per pixel:
//   1. A pixel no point reached but at least kFillNeighbours of its 8 neighbours did takes the
//      nearest of them: this fills the one-pixel holes between a surface's points without
//      growing silhouettes. The result goes to `resolved`, which picking and overlays read.
//   2. The point's id leads to its chunk (render_layout.h) and its attributes, coloured
//      by the colour mode: RGB, intensity (grey), elevation (a ramp), segment or scan (a palette).
//   3. Eye-dome lighting (Boucheny 2009, as in Potree): the pixel darkens by how much nearer its
//      8 neighbours are, in log2 of the depth, which outlines edges and steps without normals.
//      Steps below kEdlFloor are noise, not edges.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
#extension GL_GOOGLE_include_directive : require

#include "render_layout.h"

layout(local_size_x = kResolveGroupSize, local_size_y = kResolveGroupSize) in;

layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Chunks { SplatChunk chunk[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Points { uint word[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Labels { uint label[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer ScanWords { uint word[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Visibility { uint64_t pixel[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) writeonly buffer Resolved { uint64_t pixel[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer Colour { uint pixel[]; };

layout(push_constant) uniform Push { ResolvePush push; };

const uint64_t kEmpty = ~uint64_t(0);
const int kFillNeighbours = 5;
// Eye-dome lighting ignores steps under 0.4 % of the depth (log2 of 1.004): the scanner's noise
// and the slightly tilted surfels of one surface, not its edges.
const float kEdlFloor = 0.00576;
const ivec2 kNeighbours[8] = ivec2[](ivec2(-1, -1), ivec2(0, -1), ivec2(1, -1), ivec2(-1, 0), ivec2(1, 0),
                                     ivec2(-1, 1), ivec2(0, 1), ivec2(1, 1));

uint64_t visibilityAt(ivec2 p) {
  if (p.x < 0 || p.y < 0 || p.x >= int(push.width) || p.y >= int(push.height)) return kEmpty;
  return Visibility(push.visibility).pixel[uint(p.y) * push.width + uint(p.x)];
}

float depthOf(uint64_t value) {
  return uintBitsToFloat(uint(value >> 32));
}

// The neighbours' depth bits alone, as 32-bit loads of the values' upper halves: on lavapipe a
// load costs the same whatever its width, and the depths are all EDL and hole filling compare.
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer VisibilityWords { uint word[]; };

uint depthBitsAt(ivec2 p) {
  if (p.x < 0 || p.y < 0 || p.x >= int(push.width) || p.y >= int(push.height)) return kEmptyHigh;
  return VisibilityWords(push.visibility).word[2u * (uint(p.y) * push.width + uint(p.x)) + 1u];
}

// A perceptual ramp from dark blue through green to yellow (after matplotlib's viridis).
vec3 elevationRamp(float t) {
  const vec3 stops[5] = vec3[](vec3(0.267, 0.005, 0.329), vec3(0.229, 0.322, 0.546), vec3(0.128, 0.567, 0.551),
                               vec3(0.369, 0.789, 0.383), vec3(0.993, 0.906, 0.144));
  const float x = clamp(t, 0.0, 1.0) * 4.0;
  const int i = min(int(x), 3);
  return mix(stops[i], stops[i + 1], x - float(i));
}

// Distinct colours for segment labels (0: no segment, grey) and scans (scan i as label i + 1):
// hues a golden angle apart. engine/render/palette.h computes the same colours for legends.
vec3 segmentColour(uint label) {
  if (label == 0u) return vec3(0.55);
  const float hue = fract(float(label) * 0.618034);
  const vec3 k = vec3(0.0, 2.0 / 3.0, 1.0 / 3.0);
  return 0.25 + 0.7 * clamp(abs(fract(hue + k) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
}

vec3 pointColour(uint id) {
  // Only the members needed: a whole SplatChunk is 120 bytes.
  Chunks chunks = Chunks(push.chunks);
  const uint c = id >> kChunkBits;
  const uint local = id & (kChunkPoints - 1u);
  Points points = Points(chunks.chunk[c].points);
  const uint w = local * kPointWords;
  switch (push.colour_mode) {
    case kColourRgb: {
      const uint rg = points.word[w + 3], bi = points.word[w + 4];
      return vec3(float(rg & 0xFFFFu), float(rg >> 16), float(bi & 0xFFFFu)) / 65535.0;
    }
    case kColourIntensity: {
      const float intensity = float(points.word[w + 4] >> 16);
      return vec3(clamp((intensity - push.intensity_min) / max(push.intensity_max - push.intensity_min, 1.0), 0.0, 1.0));
    }
    case kColourElevation: {
      const float z = chunks.chunk[c].elevation_offset + uintBitsToFloat(points.word[w + 2]);
      return elevationRamp((z - push.elevation_min) / max(push.elevation_max - push.elevation_min, 1e-6));
    }
    case kColourScan: {
      const uint64_t scans = chunks.chunk[c].scans;
      const uint scan = scans == 0 ? 0u : (ScanWords(scans).word[local >> 1] >> ((local & 1u) * 16u)) & 0xFFFFu;
      return segmentColour(scan + 1u);
    }
    default: {
      const uint64_t labels = chunks.chunk[c].labels;
      return segmentColour(labels == 0 ? 0u : Labels(labels).label[local]);
    }
  }
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(push.width) || p.y >= int(push.height)) return;
  const uint index = uint(p.y) * push.width + uint(p.x);

  uint64_t value = visibilityAt(p);
  if (value == kEmpty) {
    int reached = 0, nearest = -1;
    uint nearest_bits = kEmptyHigh;
    for (int n = 0; n < 8; ++n) {
      // Background pixels, most of the empty ones, stop here: with none of the first four
      // neighbours reached, the other four cannot make kFillNeighbours.
      if (n == 4 && reached == 0) break;
      const uint bits = depthBitsAt(p + kNeighbours[n]);
      if (bits != kEmptyHigh) {
        ++reached;
        if (bits < nearest_bits) {
          nearest_bits = bits;
          nearest = n;
        }
      }
    }
    if (reached >= kFillNeighbours) value = visibilityAt(p + kNeighbours[nearest]);
  }
  Resolved(push.resolved).pixel[index] = value;
  if (value == kEmpty || push.chunk_count == 0) {
    Colour(push.colour).pixel[index] = push.background;
    return;
  }

  vec3 colour = pointColour(uint(value));
  if (push.edl_strength > 0.0) {
    const float log_depth = log2(depthOf(value));
    float response = 0.0;
    for (int n = 0; n < 8; ++n) {
      const uint bits = depthBitsAt(p + kNeighbours[n]);
      if (bits != kEmptyHigh) response += max(0.0, log_depth - log2(uintBitsToFloat(bits)) - kEdlFloor);
    }
    colour *= exp(-response * 300.0 / 8.0 * push.edl_strength);
  }
  Colour(push.colour).pixel[index] = packUnorm4x8(vec4(colour, 1.0));
}
