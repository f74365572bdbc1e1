// libFuzzer target for the camera file (engine/view/camera_json.h, docs/camera-json.md; what
// `plumb render --camera` reads): readCameraJson. Any input must end in a valid camera or a
// plumb::Error, never in a crash, a hang or a sanitizer report. Run by scripts/fuzz, and replayed
// in the test suite (fuzz_replay_main.cpp).

#include <cstddef>
#include <cstdint>

#include "engine/core/error.h"
#include "engine/view/camera.h"
#include "engine/view/camera_json.h"
#include "tests/fuzz/memory_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const plumb::view::Camera camera = plumb::view::readCameraJson(plumb::fuzz::memoryFile(data, size));
    // A camera the reader accepts is valid, so its matrices are finite: the renderer and the
    // grower's parameters (reco/params) take them as they are.
    if (plumb::view::findCameraProblem(camera)) __builtin_trap();
    if (!plumb::view::viewMatrix(camera).allFinite() || !plumb::view::projectionMatrix(camera).allFinite()) {
      __builtin_trap();
    }
  } catch (const plumb::Error&) {
    // Malformed input, reported: what the reader must do.
  }
  return 0;
}
