// The viewer's frame loop: one frame of input, tools, palette and picture at a time, the
// window's picture (or, with a headset session running, the eyes' and the mirror: viewer_xr.cpp).

#include "ui/viewer/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "engine/core/atomic_file.h"
#include "engine/io/png_image.h"
#include "engine/lod/node_cache.h"
#include "engine/render/point_renderer.h"

namespace plumb::viewer {
namespace {

constexpr double kMovingFrameMs = 1000.0 / 30.0;  // what a moving view aims for

}  // namespace

// --- the frame loop ----------------------------------------------------------------------------

int Viewer::run() {
  while (!quit_) {
    const Clock::time_point now = Clock::now();
    frame_ms_ = std::chrono::duration<double, std::milli>(now - last_frame_).count();
    last_frame_ = now;
    clock_frame_ms_ = script_ && !options_.script_wall_clock ? kScriptFrameMs : frame_ms_;
    frame_ms_avg_ = frames_ == 0 ? frame_ms_ : frame_ms_avg_ + 0.1 * (frame_ms_ - frame_ms_avg_);
    if (last_frame_moved_) moving_frame_ms_.push_back(frame_ms_);
    last_frame_moved_ = false;
    ++frames_;

    // An idle viewer sleeps in the event loop: nothing moves, nothing grows, nothing streams.
    const bool busy = script_ || xr_session_ || !cloud_ || (cloud_->grow && cloud_->grow->busy()) || !streamingIdle() ||
                      (cloud_->navigator && cloud_->navigator->flying()) || frames_ < 3;
    std::vector<InputEvent> events = window_.takeEvents(!busy, 0.5);

    std::optional<std::string> screenshot;
    if (script_ && !playScriptFrame(events, screenshot)) break;

    for (const InputEvent& event : events) imgui_.feed(event);
    for (const InputEvent& event : xr_panel_events_) imgui_.feed(event);  // the controller on the palette's panel
    xr_panel_events_.clear();
    jobs_.drainContinuations();  // grow snapshots into the scene, a finished import
    pollHeadset();

    const VkExtent2D size = window_.framebufferSize();
    if (size.width == 0 || size.height == 0) {
      handleEvents(events);  // a close while minimised
      continue;
    }
    autosaveProject(false);
    imgui_.beginFrame(size.width, size.height, clock_frame_ms_ * 1e-3);
    handleEvents(events);
    updateHover();
    drawPanels();
    imgui_.endFrame();
    if (!renderHeadsetFrame(screenshot.has_value(), screenshot.value_or(""))) {
      render(screenshot.has_value(), screenshot.value_or(""));
    }
  }
  if (!options_.dump_scene.empty()) {
    AtomicFile file(options_.dump_scene);
    const std::string json = scene_.toJson();
    file.write(json.data(), json.size());
    file.finish();
    file.commit();
  }
  if (script_ && !moving_frame_ms_.empty()) {
    // What navigation costs here: the frames whose camera moved, start to start.
    std::vector<double> sorted = moving_frame_ms_;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2], p90 = sorted[sorted.size() * 9 / 10];
    std::printf(
        "plumb view: %zu moving frames: median %.1f ms (%.1f fps), 90th percentile %.1f ms; budget %llu "
        "points, render scale %.2f (%.2f at the end of the last move), %s\n",
        sorted.size(), median, 1e3 / median, p90, static_cast<unsigned long long>(settings_.selection.point_budget),
        static_cast<double>(render_scale_), adaptive_quality_ ? moving_scale_ : static_cast<double>(render_scale_),
        device_.name().c_str());
  }
  reportHeadset();
  if (!splat_ms_.empty()) {
    const auto median = [](std::vector<double> values) {
      std::sort(values.begin(), values.end());
      return values[values.size() / 2];
    };
    std::printf("plumb view: GPU time of a moving frame: splat %.1f ms, resolve %.1f ms (medians)\n", median(splat_ms_),
                median(resolve_ms_));
  }
  const std::vector<std::string> messages = instance_.validationMessages();
  for (const std::string& message : messages) std::fprintf(stderr, "plumb view: validation: %s\n", message.c_str());
  if (!messages.empty()) exit_status_ = 1;
  return exit_status_;
}

// The scale of the view the navigator holds: the last frame's, which the events of this frame
// refer to (a moving view renders at a lower scale than a still one).
double Viewer::renderScale() const {
  const VkExtent2D size = window_.framebufferSize();
  if (!cloud_ || size.width == 0) return static_cast<double>(render_scale_);
  return static_cast<double>(cloud_->navigator->camera().viewport_width_px) / size.width;
}

// Every node the view wants is drawn, of the whole cloud (not of an import's preview).
bool Viewer::streamingIdle() const {
  if (!cloud_ || last_stats_.frame == 0 || !last_stats_.complete()) return false;
  const std::scoped_lock lock(load_progress_->mutex);
  return load_progress_->finished;
}

std::shared_ptr<const render::OverlayScene> Viewer::withClipBox(std::shared_ptr<const render::OverlayScene> scene) {
  if (!clip_.box) return scene;
  const std::optional<BoxHandle> lit = box_drag_ ? std::optional(box_drag_->handle()) : hovered_box_handle_;
  const bool same = box_overlay_ && box_overlay_source_ == scene && box_overlay_lit_ == lit &&
                    box_overlay_box_.centre == clip_.box->centre &&
                    box_overlay_box_.half_size == clip_.box->half_size &&
                    box_overlay_box_.yaw_rad == clip_.box->yaw_rad;
  if (!same) {
    auto overlay = std::make_shared<render::OverlayScene>(*scene);
    addClipBox(*overlay, *clip_.box, lit);
    box_overlay_ = std::move(overlay);
    box_overlay_source_ = std::move(scene);
    box_overlay_box_ = *clip_.box;
    box_overlay_lit_ = lit;
  }
  return box_overlay_;
}

// The document as a project saves it: the scene's items and the section.
// --- drawing -----------------------------------------------------------------------------------

void Viewer::render(bool screenshot, const std::string& screenshot_name) {
  if (!cloud_) {
    presentInterfaceOnly();
    if (screenshot) std::fprintf(stderr, "plumb view: no screenshot before the cloud is loaded\n");
    return;
  }
  // A moving view trades resolution and points for frame rate (dynamic resolution): towards
  // kMovingFrameMs, never below a quarter of the still view's scale; a still view is drawn in
  // full. The point budget follows the pixels, so the points per pixel stay the same.
  cloud_->navigator->update(clock_frame_ms_ * 1e-3);
  last_frame_moved_ = cloud_->navigator->takeChanged();
  if (last_frame_moved_ && adaptive_quality_) {
    const double step = std::clamp(std::sqrt(kMovingFrameMs / std::max(clock_frame_ms_, 1.0)), 0.8, 1.25);
    moving_scale_ = std::clamp(moving_scale_ * step, 0.25 * render_scale_, static_cast<double>(render_scale_));
  }
  const double scale = last_frame_moved_ && adaptive_quality_ ? moving_scale_ : render_scale_;
  render::RenderSettings frame_settings = settings_;
  frame_settings.clip = clip_.region();
  const double pixel_share = (scale * scale) / (static_cast<double>(render_scale_) * render_scale_);
  frame_settings.selection.point_budget = std::max<std::uint64_t>(
      10'000, static_cast<std::uint64_t>(static_cast<double>(settings_.selection.point_budget) * pixel_share));
  const VkExtent2D size = window_.framebufferSize();
  const int width = std::max(1, static_cast<int>(std::lround(size.width * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(size.height * scale)));
  cloud_->navigator->setViewport(width, height, static_cast<int>(size.width));
  cloud_->renderer->setOverlay(withClipBox(overlay_.update(scene_.registry())));
  const std::optional<gpu::SwapchainImage> image = swapchain_.acquire();
  if (!image) return;
  pending_screenshot_ = screenshot && swapchain_.readable();
  last_stats_ =
      cloud_->renderer->render(cloud_->navigator->camera(), frame_settings, render::NodeLoading::kStream, {&*image, 1});
  swapchain_.present(*image);
  if (options_.profile && last_frame_moved_) {
    if (const std::optional<render::GpuTimings> timings = cloud_->renderer->gpuTimings()) {
      splat_ms_.push_back(timings->splat_ms);
      resolve_ms_.push_back(timings->resolve_ms);
    }
  }
  if (screenshot) {
    if (!pending_screenshot_) {
      std::fprintf(stderr, "plumb view: this window system's images cannot be read back: no screenshot\n");
      exit_status_ = 1;
    } else {
      cloud_->renderer->waitForFrames();
      writeScreenshot(screenshot_name);
    }
    pending_screenshot_ = false;
  }
}

void Viewer::writeScreenshot(const std::string& name) {
  std::optional<io::RgbaImage> image = screenshots_.take();
  if (!image) return;
  const std::filesystem::path directory = options_.screenshot_dir.empty() ? "." : options_.screenshot_dir;
  std::filesystem::create_directories(directory);
  io::writePng(*image, (directory / name).string());
  std::printf("plumb view: screenshot %s\n", (directory / name).string().c_str());
}

// Before a cloud is ready: the palette (with the loading progress) on a cleared image.
void Viewer::presentInterfaceOnly() {
  const std::optional<gpu::SwapchainImage> image = swapchain_.acquire();
  if (!image) return;
  if (ui_frames_ >= 1) ui_timeline_.wait(ui_frames_, UINT64_MAX);
  ui_commands_.reset();
  VkCommandBuffer commands = ui_commands_.begin();
  gpu::imageBarrier(commands, image->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const render::Rgba& b = settings_.background;
  const VkClearColorValue clear{{b[0] / 255.0f, b[1] / 255.0f, b[2] / 255.0f, 1.0f}};
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(commands, image->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
  imgui_.record(commands, *image);
  gpu::submit(device_, commands, ui_timeline_, ++ui_frames_, image->acquired,
              VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, image->rendered);
  swapchain_.present(*image);
}

}  // namespace plumb::viewer
