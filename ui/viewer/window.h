#pragma once
// The viewer's GLFW window: created without a client API (Vulkan draws into it), its input
// collected as InputEvents for the frame to consume. Not thread-safe: GLFW wants the main thread.

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "ui/viewer/input_event.h"

struct GLFWwindow;

namespace plumb::viewer {

// GLFW, initialised for the process's lifetime of this object. Throws plumb::Error when there is
// no display to open windows on (the message says so, for the headless fallback).
class WindowSystem {
 public:
  WindowSystem();
  ~WindowSystem();
  WindowSystem(const WindowSystem&) = delete;
  WindowSystem& operator=(const WindowSystem&) = delete;

  // The instance extensions a Vulkan surface on this window system needs.
  std::vector<const char*> requiredInstanceExtensions() const;

  // True when GLFW can open a window here (an X server or Wayland compositor answers). Leaves
  // GLFW initialised when it is: a WindowSystem made next takes it over.
  static bool displayAvailable();
};

class Window {
 public:
  Window(const WindowSystem& system, int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  // A surface on this window; the caller (the swapchain) owns it from then on.
  VkSurfaceKHR createSurface(VkInstance instance) const;
  // The framebuffer's size in pixels; 0 x 0 while minimised.
  VkExtent2D framebufferSize() const;

  // Collects what happened since the last call, waiting up to `timeout_s` for something to
  // happen when `wait` (an idle viewer sleeps in the event loop, not in a poll). A posted
  // empty event (wakeUp) ends the wait.
  std::vector<InputEvent> takeEvents(bool wait, double timeout_s);
  // Ends a wait in takeEvents from any thread (a job finished).
  static void wakeUp();

  void setTitle(const std::string& title) const;
  void resize(int width, int height) const;

 private:
  static void onCursor(GLFWwindow* window, double x, double y);
  static void onButton(GLFWwindow* window, int button, int action, int mods);
  static void onScroll(GLFWwindow* window, double dx, double dy);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onCharacter(GLFWwindow* window, unsigned int codepoint);
  static void onClose(GLFWwindow* window);

  GLFWwindow* window_ = nullptr;
  std::vector<InputEvent> events_;
  double last_x_ = 0.0, last_y_ = 0.0;
};

}  // namespace plumb::viewer
