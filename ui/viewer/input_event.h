#pragma once
// What the viewer reacts to, from the window or from a replayed script alike: the window's
// callbacks and the script player both produce these, and the frame consumes them in order, so
// a scripted session drives exactly the code a user drives.
//
// Coordinates are window pixels (x right, y down, from the top-left corner), as GLFW reports
// them; keys and buttons are GLFW's codes.

#include <cstdint>
#include <string>

namespace plumb::viewer {

struct InputEvent {
  enum class Kind : std::uint8_t {
    kMouseMove,    // x, y
    kMouseButton,  // button, pressed, mods (at the last mouse position)
    kWheel,        // wheel_y (positive: away from the user, zoom in), at the last mouse position
    kKey,          // key, pressed, mods
    kCharacter,    // codepoint (text input)
    kClose,        // the window's close button, or a script's end
  };
  Kind kind = Kind::kMouseMove;
  double x = 0.0, y = 0.0;
  int button = 0;  // GLFW_MOUSE_BUTTON_*
  int key = 0;     // GLFW_KEY_*
  int mods = 0;    // GLFW_MOD_*
  bool pressed = false;
  double wheel_y = 0.0;
  std::uint32_t codepoint = 0;
};

}  // namespace plumb::viewer
