#pragma once
// The splat's surfels: each point drawn as a small disc in the plane of the surface around it
// (Pfister et al. 2000, "Surfels: surface elements as rendering primitives"), so that a
// surface closes at any distance with the depth of the surface itself, whatever its slant: no
// steps between splats for eye-dome lighting to outline, no square reaching past an edge seen
// at a grazing angle.
//
// Per point of a node, from its nearest neighbours among the node's points and its ancestors'
// (drawn wherever the node is, so that the node's discs fit the drawn cloud where it is the
// finest drawn; where its children are drawn too, splat_spacing.h scales them down):
//   - the spacing: the distance to its 4th nearest, the radius of a disc that closes the
//     surface wherever the scan's pattern leaves gaps (as the reference image of
//     tests/support/surface_coverage.h draws it);
//   - the normal: the least principal axis of the point and its 12 nearest, of its 40 nearest
//     where the 12 lie along one of the scanner's lines; none (the disc faces the eye) where even
//     those span no one plane, at half the radius where they lie along a line.
// The renderer estimates them once per node, before it uploads the node (surfel_estimates.h).

#include <cstdint>
#include <span>
#include <vector>

#include "engine/lod/octree_format.h"

namespace plumb::render {

// A surfel whose neighbours span no plane: its disc faces the eye (never an encoded normal,
// whose fractions stop at -32767).
constexpr std::uint32_t kFacingTheEye = 0x80008000u;

// As the splat shader reads it (shaders/render_layout.h, kSurfelWords).
struct Surfel {
  std::uint32_t normal = kFacingTheEye;  // octahedral: x | y << 16, each a signed 16-bit fraction
  float radius_m = 0.0f;                 // 0: a lone point (fewer than 4 neighbours within max_radius): one pixel
};

// The surfels of a node's `own` points (positions relative to the node's corner, inside a cube of
// side `cell_size`), their neighbours among them and the points `around` them that the renderer
// draws with the node (its ancestors', in the node's frame), which get no surfels of their own.
// Neighbours farther than `max_radius` are not looked for.
std::vector<Surfel> estimateSurfels(std::span<const lod::PackedPoint> own, std::span<const lod::PackedPoint> around,
                                    double cell_size, double max_radius);

// The octahedral encoding of a unit normal, and back (the shader's decoding is the same).
std::uint32_t encodeNormal(float x, float y, float z);
void decodeNormal(std::uint32_t packed, float& x, float& y, float& z);

}  // namespace plumb::render
