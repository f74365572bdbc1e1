#include "ui/viewer/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "engine/core/error.h"
#include "engine/gpu/vk_check.h"

namespace plumb::viewer {
namespace {

Window& owner(GLFWwindow* window) {
  return *static_cast<Window*>(glfwGetWindowUserPointer(window));
}

std::string lastGlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description != nullptr ? description : "no reason given";
}

}  // namespace

WindowSystem::WindowSystem() {
  if (glfwInit() != GLFW_TRUE) throw Error("cannot open windows: " + lastGlfwError() + " (is DISPLAY set?)");
  if (glfwVulkanSupported() != GLFW_TRUE) {
    glfwTerminate();
    throw Error("the window system offers no Vulkan surfaces (install a Vulkan loader: scripts/setup does)");
  }
}

WindowSystem::~WindowSystem() {
  glfwTerminate();
}

std::vector<const char*> WindowSystem::requiredInstanceExtensions() const {
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  return {names, names + count};
}

bool WindowSystem::displayAvailable() {
  // GLFW stays initialised for the WindowSystem that follows (its glfwInit returns at once, its
  // destructor terminates): closing the probe's connection made a server with no other client
  // (Xvfb) reset, and the viewer's own connection a moment later could fail while it did.
  return glfwInit() == GLFW_TRUE;
}

Window::Window(const WindowSystem& /*system*/, int width, int height, const std::string& title) {
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) throw Error("cannot open a window: " + lastGlfwError());
  glfwSetWindowUserPointer(window_, this);
  glfwSetCursorPosCallback(window_, onCursor);
  glfwSetMouseButtonCallback(window_, onButton);
  glfwSetScrollCallback(window_, onScroll);
  glfwSetKeyCallback(window_, onKey);
  glfwSetCharCallback(window_, onCharacter);
  glfwSetWindowCloseCallback(window_, onClose);
}

Window::~Window() {
  glfwDestroyWindow(window_);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  gpu::check(glfwCreateWindowSurface(instance, window_, nullptr, &surface), "glfwCreateWindowSurface");
  return surface;
}

VkExtent2D Window::framebufferSize() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED) == GLFW_TRUE) width = height = 0;
  return {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)};
}

std::vector<InputEvent> Window::takeEvents(bool wait, double timeout_s) {
  if (wait) {
    glfwWaitEventsTimeout(timeout_s);
  } else {
    glfwPollEvents();
  }
  std::vector<InputEvent> events;
  events.swap(events_);
  return events;
}

void Window::wakeUp() {
  glfwPostEmptyEvent();
}

void Window::setTitle(const std::string& title) const {
  glfwSetWindowTitle(window_, title.c_str());
}

void Window::resize(int width, int height) const {
  glfwSetWindowSize(window_, width, height);
}

void Window::onCursor(GLFWwindow* window, double x, double y) {
  Window& self = owner(window);
  self.last_x_ = x;
  self.last_y_ = y;
  self.events_.push_back({.kind = InputEvent::Kind::kMouseMove, .x = x, .y = y});
}

void Window::onButton(GLFWwindow* window, int button, int action, int mods) {
  Window& self = owner(window);
  self.events_.push_back({.kind = InputEvent::Kind::kMouseButton,
                          .x = self.last_x_,
                          .y = self.last_y_,
                          .button = button,
                          .mods = mods,
                          .pressed = action == GLFW_PRESS});
}

void Window::onScroll(GLFWwindow* window, double /*dx*/, double dy) {
  Window& self = owner(window);
  self.events_.push_back({.kind = InputEvent::Kind::kWheel, .x = self.last_x_, .y = self.last_y_, .wheel_y = dy});
}

void Window::onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
  if (action == GLFW_REPEAT) return;  // held keys are state: the frame sees them held
  owner(window).events_.push_back(
      {.kind = InputEvent::Kind::kKey, .key = key, .mods = mods, .pressed = action == GLFW_PRESS});
}

void Window::onCharacter(GLFWwindow* window, unsigned int codepoint) {
  owner(window).events_.push_back({.kind = InputEvent::Kind::kCharacter, .codepoint = codepoint});
}

void Window::onClose(GLFWwindow* window) {
  owner(window).events_.push_back({.kind = InputEvent::Kind::kClose});
}

}  // namespace plumb::viewer
