// Layouts and constants shared by the renderer's GLSL (shaders/*.glsl) and C++ (engine/render).
// Only 32- and 64-bit scalars and arrays of 32-bit scalars, whose std430 layout equals the C++
// layout with natural alignment; engine/render static_asserts the sizes.
#ifndef PLUMB_SHADERS_RENDER_LAYOUT_H
#define PLUMB_SHADERS_RENDER_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace plumb::shader {
using uint = std::uint32_t;
using std::uint64_t;
#endif

// A node's points are drawn in chunks of at most 2^kChunkBits, one splat work group each, so
// that big and small nodes spread evenly over the GPU. A point's id in the visibility buffer is
// its chunk's index << kChunkBits | its index in the chunk: the resolve finds the chunk without
// a search, and 2^20 chunks of a frame have room for 4 billion points.
const uint kChunkBits = 12u;
const uint kChunkPoints = 1u << kChunkBits;
const uint kSplatGroupSize = 128;
const uint kResolveGroupSize = 8;  // the resolve runs on 8 x 8 pixel tiles

// The words of one stored point (lod::PackedPoint): x, y, z as floats relative to the node's
// origin, then r | g << 16, then b | intensity << 16.
const uint kPointWords = 5;

// The visibility buffer's value for a pixel no point reached: above every depth << 32 | id.
const uint kEmptyHigh = 0xFFFFFFFFu;

const uint kColourRgb = 0u;
const uint kColourIntensity = 1u;
const uint kColourElevation = 2u;
const uint kColourSegment = 3u;
const uint kColourScan = 4u;

// One chunk of a node's points, as the splat and the resolve see it.
struct SplatChunk {
  float clip_from_node[16];  // column-major: node position -> (pixel x, pixel y, _, 1) * w
  float depth_from_node[4];  // the row giving the view depth (metres in front of the eye)
  uint64_t points;           // device address of the chunk's first point
  uint64_t labels;           // device address of the chunk's first segment label (uint); 0: none
  // Device address of the chunk's first scan index (16 bits each, two to a word; lod::NodePoints::scans);
  // 0: the cloud is one scan. Chunks start at multiples of kChunkPoints, so it is word-aligned.
  uint64_t scans;
  uint64_t surfels;        // device address of the chunk's first Surfel (kSurfelWords each)
  uint point_count;        // at most kChunkPoints
  float elevation_offset;  // the node origin's z above ResolvePush's elevation base
  // Each point is a disc in the plane of its surface (engine/render/surfels.h), of its surfel's
  // radius times its octant's scale: the drawn cloud's density there against the node's own
  // (engine/render/splat_spacing.h). Octant i as lod::CellKey::child numbers them, split at
  // half_cell_m (the node's half size) in node coordinates.
  float octant_scale[8];
  float half_cell_m;
  // 0: no disc of the chunk reaches a pixel's radius (its node lies too far): each point its
  // pixel, without the discs' work.
  uint discs;
  float clip_offset[3];  // the node origin less the clip region's anchor (ClipPlanes)
};

// The region the splat keeps (engine/render/clip_region.h): half-spaces, each kept where
// dot(plane.xyz, p) + plane.w >= 0, p a point's position less the region's anchor. The first
// box_planes (0 or 6) are a box's faces, a point inside it when on the kept side of all six, and
// keep_outside_box keeps the others instead; every further plane must hold as well.
const uint kMaxClipPlanes = 32u;

struct ClipPlanes {
  uint plane_count;  // the box's included
  uint box_planes;
  uint keep_outside_box;
  uint reserved;
  float planes[4 * kMaxClipPlanes];
};

// What each point covers (render::SplatShape): its pixel; a square facing the eye of half-side
// its surfel's radius; its surfel's disc.
const uint kSplatPoint = 0u;
const uint kSplatSquare = 1u;
const uint kSplatSurfel = 2u;

// A surfel (engine/render/surfels.h): the normal, octahedral (x | y << 16, signed 16-bit
// fractions; kSurfelFacingTheEye: none, the disc faces the eye), and the disc's radius in
// metres as a float (0: one pixel).
const uint kSurfelWords = 2;
const uint kSurfelFacingTheEye = 0x80008000u;

// The largest half-side of a point's square (kSplatSquare) on screen, in pixels: a square nearer
// the eye is drawn this size (its cost grows with its area). Discs are cast whole.
const uint kMaxSplatHalfPx = 512u;

// The splat covers a point's disc or square itself where that takes at most
// kMaxDirectSplatWork loop iterations (its rows times its columns and one); a wider one it lists
// for the wide pass (splat_wide.comp.glsl) in blocks of up to kWideSplatGroupSize rows, one work
// group per block and an invocation per row. For lavapipe stops every loop of an invocation (of
// each SIMD vector of them) after 65,535 iterations in all, silently (gallivm's
// LP_MAX_TGSI_LOOP_ITERATIONS): a disc near the eye that one invocation covered was cut off part
// way. Now an invocation of the splat runs at most 32 footprints of 1,024 iterations
// (kChunkPoints / kSplatGroupSize), and one of the wide pass a row of at most 16,384 pixels.
// The wide pass also shares a big disc's rows out among many invocations where one had them all.
const uint kMaxDirectSplatWork = 1024u;
const uint kWideSplatGroupSize = 256u;
// The wide pass's work groups are a grid this many wide (a dispatch's x may be 65,535 at least).
const uint kWideSplatGroupsX = 32768u;
// The list of blocks for the wide pass: this header, then per block two words: its point's id,
// and its first row | its number of rows << 16.
struct WideSplatHeader {
  uint groups[3];  // the wide pass's work groups, its indirect dispatch (z is 1)
  uint claimed;    // blocks claimed, some perhaps beyond the capacity
  uint listed;     // blocks written, each of those below it
  uint reserved;
};

struct SplatPush {
  uint64_t chunks;      // SplatChunk[chunk_count]
  uint64_t visibility;  // uint64_t[width * height], cleared to all ones
  uint width;
  uint height;
  uint chunk_count;
  float near_m;   // points nearer than this to the eye are clipped
  uint64_t clip;  // ClipPlanes; 0: every point kept
  // A length of 1 m at view depth d spans pixels_per_metre / d pixels (perspective), or
  // pixels_per_metre at any depth (orthographic): a point's radius on screen.
  float pixels_per_metre;
  uint perspective;
  uint shape;  // kSplatPoint, kSplatSquare or kSplatSurfel
  uint reserved;
  uint64_t wide;       // WideSplatHeader, then the blocks listed for the wide pass
  uint wide_capacity;  // blocks the list has room for
  uint reserved2;
};

struct ResolvePush {
  uint64_t chunks;      // as in SplatPush
  uint64_t visibility;  // read: the splat's result
  uint64_t resolved;    // written: the visibility with one-pixel holes filled (picking, overlays)
  uint64_t colour;      // written: RGBA8 per pixel, R in the lowest byte
  uint width;
  uint height;
  uint chunk_count;
  uint colour_mode;
  float elevation_min;  // the elevation colour ramp, above the elevation base
  float elevation_max;
  float intensity_min;  // the intensities drawn black and white (engine/render/intensity_range.h)
  float intensity_max;
  float edl_strength;  // eye-dome lighting; 0: off
  uint background;     // RGBA8 of empty pixels
};

// Overlay vertices (shaders/overlay.*.glsl), positions relative to the eye. A line is drawn as a
// quad: each of its six vertices holds both ends and pushes itself sideways by offset_px.x; a
// marker's six vertices share its centre and push out by offset_px.
const uint kOverlayLine = 1u;    // flags: expand sideways from the line a -> other
const uint kOverlayMarker = 2u;  // flags: offset_px is a screen offset from position
const uint kOverlayOnTop = 4u;   // flags: drawn even where the cloud is nearer (snap markers)

struct OverlayVertex {
  float position[3];
  float other[3];  // the line's other end (kOverlayLine)
  float offset_px[2];
  uint colour;  // RGBA8, R in the lowest byte, straight alpha
  uint flags;
};

struct OverlayPush {
  uint64_t vertices;        // OverlayVertex[]
  uint64_t resolved;        // the resolved visibility: the overlay's depth test
  float clip_from_eye[16];  // Vulkan clip space from eye-relative world positions
  float depth_from_eye[4];  // the row giving the view depth
  uint width;
  uint height;
  float depth_tolerance;  // a fragment hides behind the cloud beyond depth * (1 + this) + 1 cm
  uint reserved;
};

// The depth pass (shaders/depth_out.*.glsl): the resolved visibility's view depths into a depth
// image, as a Vulkan perspective projection maps them (0 at the near plane, 1 at the far one),
// for a headset runtime's reprojection (XR_KHR_composition_layer_depth).
struct DepthOutPush {
  uint64_t resolved;  // the resolved visibility, one uint64_t a pixel
  uint width;
  float near_m;
  float far_m;
  uint reserved;
};

// The bare splat of the benchmark (shaders/bare_splat.comp.glsl): one flat array of points and
// one transform, one invocation per point; what the renderer's splat is measured against.
struct BareSplatPush {
  uint64_t points;
  uint64_t visibility;
  float clip_from_points[16];
  float depth_from_points[4];
  uint width;
  uint height;
  uint point_count;
  float near_m;
};

#ifdef __cplusplus
}  // namespace plumb::shader
#endif

#endif
