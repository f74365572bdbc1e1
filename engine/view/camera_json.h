#pragma once
// Cameras as JSON files ("plumb-camera", version 1; the format is docs/camera-json.md).
//
// Both functions are thread-safe as long as no two calls write the same path.

#include <string>

#include "engine/view/camera.h"

namespace plumb::view {

// The format version this build writes and the newest it reads.
constexpr int kCameraJsonVersion = 1;

// Reads and validates a camera file. `position` and `target` are required, every other field has
// the default of Camera. Throws plumb::Error whose message starts with the quoted path and names
// the field (or, for text that is not JSON, the byte offset) when: the file cannot be read; it is
// not JSON; the top level is not an object; `format` is not "plumb-camera"; `version` is newer
// than kCameraJsonVersion ("written by a newer Plumb") or not a positive integer; a required
// field is missing; a field has the wrong type or is unknown; a number is not finite or out of
// range; the camera breaks a rule of findCameraProblem.
Camera readCameraJson(const std::string& path);

// Writes `camera` (which must be valid: plumb::Error otherwise, naming the path) with every field,
// atomically through AtomicFile. Numbers are written so that readCameraJson returns them bit for
// bit. Throws plumb::Error when the file cannot be written.
void writeCameraJson(const Camera& camera, const std::string& path);

}  // namespace plumb::view
