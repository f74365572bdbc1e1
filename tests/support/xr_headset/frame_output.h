#pragma once
// What the simulated headset writes for the tests to check, in the folder PLUMB_XR_HEADSET_OUT
// names: one line of frames.jsonl per xrEndFrame, and the captured frames' layer images as PNGs
// (frame-NNNN-eye-E.png, frame-NNNN-quad-K.png). The content follows the frame the application
// submitted (OpenXR 1.0 specification, chapter 10 "Rendering", section "Frame Submission").

#include <cstdint>
#include <string>
#include <vector>

#include "tests/support/xr_headset/pose_math.h"

namespace plumb::xr_headset {

struct SubmittedView {
  Pose pose;  // in the LOCAL/STAGE space (the script's), whatever space the layer named
  XrFovf fov{};
  XrRect2Di image_rect{};
  bool depth = false;                 // an XrCompositionLayerDepthInfoKHR came with it
  float near_z = 0.0f, far_z = 0.0f;  // its planes, when it did
};

struct SubmittedFrame {
  std::uint64_t frame = 0;
  XrTime display_time = 0;
  std::uint32_t layer_count = 0;
  std::vector<SubmittedView> views;  // of every projection layer, in order
  std::uint32_t quad_count = 0;
};

// The JSON line for `frame` (no newline): {"frame", "display_time", "layers", "views": [{"pose":
// {"position", "orientation" [x, y, z, w]}, "fov" {"left", "right", "up", "down"} in radians,
// "image_rect" [x, y, width, height], "depth"}], "quads"}.
std::string frameJsonLine(const SubmittedFrame& frame);

// Appends `line` and a newline to `folder`/frames.jsonl. False on failure (reported on stderr).
bool appendFrameLine(const std::string& folder, const std::string& line);

// "frame-0007-eye-1.png" and "frame-0007-quad-0.png": the frame index zero-padded to 4 digits.
std::string eyeImageName(std::uint64_t frame, std::uint32_t eye);
std::string quadImageName(std::uint64_t frame, std::uint32_t quad);
std::string latestEyeImageName(std::uint32_t eye);                   // "latest-eye-E.png"
std::string depthImageName(std::uint64_t frame, std::uint32_t eye);  // "frame-NNNN-depth-E.pfm"
std::string latestDepthImageName(std::uint32_t eye);                 // "latest-depth-E.pfm"

// Writes depths (one float a pixel, rows top to bottom) as a Portable Float Map at `folder`/`name`
// ("Pf", little-endian, rows bottom to top as that format has them), through a temporary file
// renamed into place. False on failure (reported on stderr).
bool writePfm(const std::string& folder, const std::string& name, std::uint32_t width, std::uint32_t height,
              const std::vector<float>& depths);

// Writes RGBA8 pixels (rows top to bottom) as a PNG at `folder`/`name`, through a temporary file
// renamed into place so a reader never sees half a file. False on failure (reported on stderr).
bool writePng(const std::string& folder, const std::string& name, std::uint32_t width, std::uint32_t height,
              const std::vector<std::uint8_t>& rgba);

}  // namespace plumb::xr_headset
