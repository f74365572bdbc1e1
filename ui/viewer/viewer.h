#pragma once
// The viewer's frame loop and state (viewer_app.h is the entry point). Internal to ui/viewer:
// viewer.cpp makes the viewer and brings its project and cloud, viewer_frame.cpp runs frames,
// viewer_input.cpp turns the window's events and a script's steps into tool actions,
// viewer_tools.cpp holds those actions, viewer_xr.cpp the headset, viewer_panels.cpp the palette.

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/commands.h"
#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/gpu/swapchain.h"
#include "engine/gpu/timeline.h"
#include "engine/jobs/job_system.h"
#include "engine/lod/cube.h"
#include "engine/render/point_renderer.h"
#include "reco/parameters.h"
#include "ui/viewer/clip_box_handles.h"
#include "ui/viewer/drawing_tools.h"
#include "ui/viewer/grow_session.h"
#include "ui/viewer/imgui_layer.h"
#include "ui/viewer/measure_tool.h"
#include "ui/viewer/navigation.h"
#include "ui/viewer/project_session.h"
#include "ui/viewer/scene_overlay.h"
#include "ui/viewer/scene_state.h"
#include "ui/viewer/screenshot.h"
#include "ui/viewer/session_script.h"
#include "ui/viewer/snapping.h"
#include "ui/viewer/viewer_app.h"
#include "ui/viewer/window.h"
#include "ui/xr/hand_panel.h"
#include "ui/xr/stage.h"

namespace plumb::lod {
class NodeCache;
class Octree;
}  // namespace plumb::lod
namespace plumb::xr {
class Runtime;
class Session;
struct HeadsetFrame;
}  // namespace plumb::xr

namespace plumb::viewer {

// What the loaded cloud brings; made when the cloud is ready (an import runs in the background).
struct LoadedCloud {
  std::shared_ptr<const lod::Octree> octree;
  std::string temporary;  // an imported octree's file, removed with the cloud
  lod::Box3 framing{};    // the cloud's bulk, without its stray points (lod/framing.h): what views frame
  std::unique_ptr<lod::NodeCache> cache;
  std::unique_ptr<render::PointRenderer> renderer;
  std::unique_ptr<Navigator> navigator;
  std::unique_ptr<GrowSession> grow;
  ~LoadedCloud();
};

// The view a click is made in, which sets its detail: a camera and the screen the user sees
// (the window, or a headset's eye at its full resolution), pixels.
struct ClickView {
  view::Camera camera;
  double width_px = 0.0, height_px = 0.0;
};

// Where a pointer is, for the tools: the view it points through and its pixel there. The
// mouse: the window's camera and the cursor, picking from the last frame; a controller: a view
// along its ray, its centre pixel, picking from a frame of that view rendered on demand.
struct PointerView {
  view::Camera camera;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();      // in the camera's viewport
  Eigen::Vector2d motion_px = Eigen::Vector2d::Zero();  // since the last frame, in that view
  PointPicker pick;                                     // the cloud's point near a pixel; null: none
  ClickView click_view;                                 // whose detail a grow from here takes
};

// Progress of the background work that brings the cloud (demo generation, an import).
struct LoadProgress {
  std::mutex mutex;
  std::string phase = "starting";
  double fraction = 0.0;
  std::optional<std::string> error;
  std::vector<std::string> temporaries;  // an import's octrees (a preview, the whole), removed by the viewer
  bool finished = false;                 // the whole cloud is open (a preview may have shown before)
};

// The grow tool's panel values: the user's settings and what the last click derived.
struct GrowPanel {
  float plane_threshold_m = 0.02f;  // t_p where the user sets it
  bool threshold_from_data = true;  // t_p from the noise measured at each click instead
  // The Detail combo's entry: 0 from the view (following the data), 1 from the view with the
  // paper's densities alone (milliseconds, coarser on dense scans), then low, medium, high and full.
  int detail = 0;
  std::optional<reco::GrowParameters> last;
  std::optional<reco::DataAtClick> last_data;  // the cloud at the last click
  std::optional<GrowUpdate> last_update;       // its newest snapshot's statistics
  bool inside_section = false;                 // grows take only the points the section keeps
};

class Viewer {
 public:
  explicit Viewer(const ViewerOptions& options);
  ~Viewer();
  int run();

 private:
  // --- frame steps (viewer.cpp, viewer_frame.cpp, viewer_input.cpp, viewer_tools.cpp) ---
  void startLoading();
  // Shows `octree`; a `preview` of an import is replaced by the whole cloud when that is ready.
  void openCloud(std::shared_ptr<const lod::Octree> octree, std::string temporary, std::optional<view::Camera> home,
                 bool preview = false);
  bool playScriptFrame(std::vector<InputEvent>& events, std::optional<std::string>& screenshot);
  void handleEvents(const std::vector<InputEvent>& events);
  void handleViewEvent(const InputEvent& event);
  void click(const PointerView& at);
  bool clipBoxEvent(const InputEvent& event);
  std::shared_ptr<const render::OverlayScene> withClipBox(std::shared_ptr<const render::OverlayScene> scene);
  bool drawingKey(const InputEvent& event);
  PointerView mousePointer(double x_px, double y_px);
  Pointer pointerAt(const PointerView& at, bool pick_point);
  void selectAt(const PointerView& at);
  void cornerOfSelected();
  void groupSelected();
  void startGrow(const Eigen::Vector3d& picked, const ClickView& view);
  ClickView desktopClickView() const;
  std::optional<reco::GrowParameters> clickParameters(const Eigen::Vector3d& picked,
                                                      const std::optional<reco::DataAtClick>& data,
                                                      const ClickView& view) const;
  void setTool(Tool tool);
  void updateHover();
  void hoverAt(const std::optional<PointerView>& at);
  void undo();
  void redo();
  void deleteSelected();
  void openProject();
  cad::Project currentProject() const;
  std::uint64_t documentState() const;
  void saveProject();
  void reportMemory(const std::string& label) const;
  void autosaveProject(bool now);
  void exportProject();
  void render(bool screenshot, const std::string& screenshot_name);
  void presentInterfaceOnly();
  std::optional<Eigen::Vector3d> pickAt(double x_px, double y_px);
  double renderScale() const;
  bool streamingIdle() const;
  void writeScreenshot(const std::string& name);

  // --- the headset (viewer_xr.cpp) ---
  static std::unique_ptr<xr::Runtime> connectHeadset();
  void startHeadsetSession();
  void pollHeadset();
  // Renders a headset frame (each eye, the window mirroring the left one) when a session runs;
  // false when none does and the window is the desktop's.
  bool renderHeadsetFrame(bool screenshot, const std::string& screenshot_name);
  std::optional<PointerView> controllerPointer(const view::Camera& left_eye);
  void headsetControllers(const view::Camera& left_eye);
  void moveInHeadset(const xr::HeadsetFrame& frame);
  void placeHeadsetPanel();
  bool pointAtHeadsetPanel();
  void drawHeadsetPanel();
  void adaptHeadsetBudget(const xr::HeadsetFrame& frame);
  std::uint64_t headsetBudget() const;  // the eyes' point budget now
  void drawHeadsetControls();
  void reportHeadset() const;

  // --- the palette (viewer_panels.cpp) ---
  void drawPanels();
  void placeInColumn(bool right);
  void endInColumn(bool right);
  void drawToolsPanel();
  void drawDrawingToolState();
  void drawGrowPanel();
  void drawSegmentsPanel();
  void drawMeasureToolState();
  void drawMeasurementLabels();
  void drawViewPanel();
  void drawScanLegend();
  void drawSectionControls();
  void drawClipPlaneControls();
  void showElevationOfSelected();
  void clipAtSelectedPlane();
  bool clipFits(std::size_t added, const char* what);
  // The one selected segment, else null with a message that `what` needs one.
  const Segment* theSelectedSegment(const std::string& what);
  void drawProjectPanel();
  void drawStatusBar();

  ViewerOptions options_;
  ProjectSession project_;  // first: a bad project file fails before any window opens
  WindowSystem windows_;
  // The headset's runtime (--xr), before the instance and the device: it makes them.
  std::unique_ptr<xr::Runtime> xr_runtime_;
  gpu::Instance instance_;
  Window window_;
  VkSurfaceKHR surface_;  // made before the device (which must present to it); the swapchain owns it
  gpu::Device device_;
  gpu::Swapchain swapchain_;
  gpu::MemoryAllocator allocator_;
  ImguiLayer imgui_;
  ScreenshotCopy screenshots_;
  jobs::JobSystem jobs_;  // before the cloud: the cache waits for loads the jobs run
  SceneState scene_;
  DrawingTools drawing_{scene_};
  MeasureTool measure_{scene_};
  SceneOverlay overlay_;
  std::unique_ptr<LoadedCloud> cloud_;
  std::shared_ptr<LoadProgress> load_progress_ = std::make_shared<LoadProgress>();

  // Presenting the palette alone while no cloud is loaded yet.
  gpu::CommandPool ui_commands_;
  gpu::TimelineSemaphore ui_timeline_;
  std::uint64_t ui_frames_ = 0;

  bool pending_screenshot_ = false;  // the present hook copies this frame's image
  std::optional<ScriptPlayer> script_;
  int exit_status_ = 0;
  bool quit_ = false;

  // The headset: a session while one runs, where its stage lies in the world (placed at the
  // session's first frame where the desktop camera is), the trigger as last read.
  std::unique_ptr<xr::Session> xr_session_;
  std::optional<xr::StagePlacement> xr_stage_;
  double xr_resolution_scale_ = 1.0;
  bool xr_trigger_held_ = false;
  bool xr_lock_held_ = false;                    // the right controller's A: the drawing tools' direction locked
  std::optional<Eigen::Vector3d> xr_aim_point_;  // what the right controller aimed at last frame
  // The palette on a panel in the left hand (while it is tracked), and the mouse events the right
  // controller makes on it, for the palette's next frame.
  std::optional<xr::HandPanel> xr_panel_;
  std::vector<InputEvent> xr_panel_events_;
  bool xr_panel_pressed_ = false;
  bool xr_panel_unavailable_said_ = false;
  bool xr_turn_held_ = false;       // the right thumbstick, pushed aside: one snap turn a push
  bool xr_secondary_held_ = false;  // B or Y: one toggle between 1:1 and the model a press
  bool xr_model_ = false;           // the model on a table (else 1:1)
  // The hands squeezing the world (bit 0 left, bit 1 right), the placement and hold they began with.
  struct HeadsetGrab {
    int hands = 0;
    xr::StagePlacement start;
    xr::Hold from;
  };
  std::optional<HeadsetGrab> xr_grab_;
  std::uint64_t xr_frames_ = 0;
  // The share of the point budget the eyes draw, following the frame time towards the headset's
  // rate (a session on the wall clock only: a script's frames keep the whole budget).
  double xr_budget_share_ = 1.0;
  std::chrono::steady_clock::time_point xr_last_frame_{};
  std::vector<double> xr_frame_ms_, xr_eye_gpu_ms_;  // wall time a headset frame; GPU time an eye (--profile)
  std::string xr_message_;                           // the headset's last state or problem, for the palette

  render::RenderSettings settings_;
  view::ClipSettings clip_;                      // the View panel's section: each frame's settings_.clip
  std::optional<BoxDrag> box_drag_;              // a clip box handle being dragged
  std::optional<BoxHandle> hovered_box_handle_;  // the handle under the cursor, lit
  std::shared_ptr<const render::OverlayScene> box_overlay_, box_overlay_source_;  // withClipBox's last
  view::ClipBox box_overlay_box_;
  std::optional<BoxHandle> box_overlay_lit_;
  float render_scale_ = 1.0f;     // of a still view
  double moving_scale_ = 1.0;     // of a moving view, adapted to the frame time
  bool adaptive_quality_ = true;  // lower resolution and budget while moving
  render::FrameStats last_stats_;
  GrowPanel grow_panel_;
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_frame_ = Clock::now();
  double frame_ms_ = 0.0;        // the last frame, start to start
  double clock_frame_ms_ = 0.0;  // what the last frame lasted for the viewer's behaviour (ScriptClock)
  double frame_ms_avg_ = 0.0;    // smoothed, for the palette
  std::uint64_t frames_ = 0;
  bool last_frame_moved_ = false;              // the camera changed in the frame just drawn
  std::vector<double> moving_frame_ms_;        // frame times while the camera moved (scripted runs report them)
  std::vector<double> splat_ms_, resolve_ms_;  // GPU times of moving frames (ViewerOptions::profile)
  double mouse_x_ = 0.0, mouse_y_ = 0.0;       // window pixels
  Eigen::Vector2d hovered_px_ = Eigen::Vector2d::Zero();  // render pixels at the last hover
  bool control_held_ = false;
  bool shift_held_ = false;
  std::string project_message_;
  float left_column_y_ = 10.0f,
        right_column_y_ = 10.0f;  // where the next panel of each column goes  // the last save's or export's outcome
  // The name fields of the segment list: the item they edit, and the text as typed.
  ecs::Entity rename_entity_ = ecs::kNullEntity, group_entity_ = ecs::kNullEntity;
  char rename_buffer_[128] = {}, group_buffer_[128] = {};
};

}  // namespace plumb::viewer
