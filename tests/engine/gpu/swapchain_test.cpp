// A window's swapchain on lavapipe with validation on, in a GLFW window on the X server that
// ctest starts with xvfb-run: frames presented, the window resized (the swapchain is rebuilt to
// the new size), minimised (frames are skipped) and restored.

#include "engine/gpu/swapchain.h"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/render/point_renderer.h"
#include "tests/engine/render/render_scene.h"
#include "tests/support/gpu_test.h"

namespace plumb::gpu {
namespace {

class Window {
 public:
  Window(int width, int height) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(width, height, "plumb swapchain test", nullptr, nullptr);
  }
  ~Window() {
    if (window_ != nullptr) glfwDestroyWindow(window_);
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* handle() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

TEST(Swapchain, PresentsThroughResizeAndMinimise) {
  ASSERT_EQ(glfwInit(), GLFW_TRUE) << "no X server: ctest runs this test under xvfb-run";
  ASSERT_EQ(glfwVulkanSupported(), GLFW_TRUE);
  std::uint32_t count = 0;
  const char** required = glfwGetRequiredInstanceExtensions(&count);
  const Instance instance({.validation = true}, std::vector<const char*>(required, required + count));
  {
    const Window window(320, 240);
    ASSERT_NE(window.handle(), nullptr);
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    check(glfwCreateWindowSurface(instance.handle(), window.handle(), nullptr, &surface), "glfwCreateWindowSurface");
    DeviceChoice choice = test::testDeviceChoice();
    choice.present_to = surface;
    const Device device(instance, choice);
    bool minimised = false;  // Xvfb has no window manager to iconify with: the size says it
    Swapchain swapchain(instance, device, surface, [&] {
      int width = 0, height = 0;
      glfwGetFramebufferSize(window.handle(), &width, &height);
      return minimised ? VkExtent2D{0, 0}
                       : VkExtent2D{static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)};
    });

    const test::TempDirectory directory("plumb_swapchain_test");
    lod::NodeCache nodes(lod::Octree::open(test::buildWallScene(directory)), 64 << 20);
    MemoryAllocator allocator(device);
    render::PointRenderer renderer(device, allocator, nodes);
    int presented = 0;
    auto frames = [&](int count_wanted) {
      for (int frame = 0; frame < count_wanted; ++frame) {
        glfwPollEvents();
        const std::optional<SwapchainImage> image = swapchain.acquire();
        if (!image) continue;
        view::Camera camera =
            test::wallSceneFront(static_cast<int>(image->extent.width), static_cast<int>(image->extent.height));
        renderer.render(camera, {}, render::NodeLoading::kWait, {&*image, 1});
        swapchain.present(*image);
        ++presented;
      }
    };
    frames(5);
    EXPECT_EQ(presented, 5);
    EXPECT_EQ(swapchain.extent().width, 320u);
    EXPECT_EQ(swapchain.extent().height, 240u);

    glfwSetWindowSize(window.handle(), 480, 300);
    for (int i = 0; i < 100; ++i) {
      glfwPollEvents();
      int width = 0, height = 0;
      glfwGetFramebufferSize(window.handle(), &width, &height);
      if (width == 480 && height == 300) break;
    }
    frames(5);
    // With PLUMB_TEST_SCREENSHOT=FILE.xwd, the screen as it is now, to be looked at (xwd, x11-apps).
    if (const char* screenshot = std::getenv("PLUMB_TEST_SCREENSHOT")) {
      vkDeviceWaitIdle(device.handle());
      const std::string command = std::string("xwd -root -silent -out ") + screenshot;
      EXPECT_EQ(std::system(command.c_str()), 0) << command;
    }
    EXPECT_EQ(presented, 10);
    EXPECT_EQ(swapchain.extent().width, 480u);
    EXPECT_EQ(swapchain.extent().height, 300u);
    EXPECT_GE(swapchain.rebuilds(), 1u);

    minimised = true;
    frames(3);
    EXPECT_EQ(presented, 10) << "a minimised window presents nothing";
    minimised = false;
    frames(3);
    EXPECT_EQ(presented, 13);
  }
  glfwTerminate();
  test::expectNoValidationMessages(instance);
}

}  // namespace
}  // namespace plumb::gpu
