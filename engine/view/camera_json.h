#pragma once
// Cameras as JSON files ("plumb-camera", version 1; the format is docs/camera-json.md).
//
// Every function is thread-safe as long as no two calls write the same path.

#include <string>
#include <string_view>

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

// A camera inside another JSON file (the project file, docs/project-file.md): the text of one JSON
// object with every field of a camera file except `format` and `version`. `camera` must be valid
// (asserted; findCameraProblem says why not). Numbers are written so that cameraFromJsonObject
// returns them bit for bit. Thread-safe.
std::string cameraJsonObject(const Camera& camera);

// The camera of `object_text`, the text of the JSON value at `field` (e.g. "camera") in the file
// `path`, read with the rules of readCameraJson, except that the value must be an object and that
// `format` and `version` are unknown fields there. Throws plumb::Error "'<path>': field
// '<field>.<name>': <what>" (or "field '<field>'" when the value is not an object). Thread-safe.
Camera cameraFromJsonObject(std::string_view object_text, const std::string& path, std::string_view field);

}  // namespace plumb::view
