// The tools' actions at the pointer: picking, selecting, growing, the drawing tools' clicks
// and hover, undo and redo.

#include "ui/viewer/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>
#include <variant>

#include "engine/lod/octree.h"
#include "reco/data_at_click.h"
#include "ui/viewer/snapping.h"
#include "ui/viewer/view_at_click.h"

namespace plumb::viewer {

std::optional<Eigen::Vector3d> Viewer::pickAt(double x_px, double y_px) {
  if (!cloud_ || last_stats_.frame == 0) return std::nullopt;
  const std::optional<render::PickedPoint> picked =
      cloud_->renderer->pick(static_cast<int>(x_px), static_cast<int>(y_px), 4);
  if (!picked) return std::nullopt;
  return Eigen::Vector3d(picked->position[0], picked->position[1], picked->position[2]);
}

// The mouse at (x, y) (render pixels) in the window's view.
PointerView Viewer::mousePointer(double x_px, double y_px) {
  PointerView at;
  at.camera = cloud_->navigator->camera();
  at.pixel = Eigen::Vector2d(x_px, y_px);
  at.motion_px = at.pixel - hovered_px_;
  at.pick = [this](double x, double y) { return pickAt(x, y); };
  at.click_view = desktopClickView();
  return at;
}

// What the pointer snaps to, with its ray and movement; a click also asks for the cloud's point
// under it.
Pointer Viewer::pointerAt(const PointerView& at, bool pick_point) {
  Pointer pointer;
  pointer.snap =
      snapCursor(scene_.registry(), at.camera, at.pixel.x(), at.pixel.y(), pick_point ? at.pick : PointPicker{});
  pointer.ray = view::rayThroughPixel(at.camera, at.pixel.x(), at.pixel.y());
  pointer.pixel = at.pixel;
  pointer.motion_px = at.motion_px;
  return pointer;
}

// Navigate: a click selects the polygon or segment under the cursor (Ctrl adds or removes).
void Viewer::selectAt(const PointerView& at) {
  const double x_px = at.pixel.x(), y_px = at.pixel.y();
  ecs::Entity entity = polygonAt(scene_.registry(), at.camera, x_px, y_px);
  if (entity == ecs::kNullEntity) {
    SnapOptions walls_too;
    walls_too.edge_on_planes = true;
    const std::optional<Snap> snap = snapCursor(scene_.registry(), at.camera, x_px, y_px, {}, walls_too);
    if (snap && snap->kind == Snap::Kind::kPlane) entity = snap->source;
  }
  if (entity != ecs::kNullEntity) {
    scene_.select(entity, control_held_);
  } else if (!control_held_) {
    scene_.clearSelection();
  }
}

void Viewer::cornerOfSelected() {
  const std::variant<ecs::Entity, std::string> made = scene_.addCornerOfSelected();
  const std::string message = std::holds_alternative<std::string>(made)
                                  ? "no corner: " + std::get<std::string>(made)
                                  : scene_.registry().get<Corner>(std::get<ecs::Entity>(made)).name;
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t.drawing.message = message; });
}

const Segment* Viewer::theSelectedSegment(const std::string& what) {
  const Segment* segment = nullptr;
  std::size_t segments = 0;
  for (const ecs::Entity entity : scene_.selected()) {
    if (const Segment* found = scene_.registry().tryGet<Segment>(entity)) {
      segment = found;
      ++segments;
    }
  }
  if (segments == 1) return segment;
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) {
    t.drawing.message = what + ": select one segment (" + std::to_string(segments) + " selected)";
  });
  return nullptr;
}

void Viewer::showElevationOfSelected() {
  const Segment* segment = theSelectedSegment("elevation");
  if (!cloud_ || segment == nullptr) return;
  // The view spans the segment, a little more (its outline's area gives its size).
  const double height_m = std::max(1.0, 1.5 * std::sqrt(std::max(segment->area_m2, 0.0)));
  cloud_->navigator->showElevation(segment->plane.centroid, segment->plane.normal, height_m);
}

// Whether the section, with `added` more planes (a slice's or a slab's two, a box's six, a clip
// plane), stays within the planes the splat takes; else the palette says why not.
bool Viewer::clipFits(std::size_t added, const char* what) {
  const view::ClipRegion region = clip_.region();
  if (region.planes.size() + (region.box ? 6 : 0) + added <= view::ClipRegion::kMaxPlanes) return true;
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) {
    t.drawing.message = std::string(what) + ": no more clip planes (at most " +
                        std::to_string(view::ClipRegion::kMaxPlanes) +
                        ", with a slice's and a slab's two and a box's six): remove some";
  });
  return false;
}

// A clip plane at the one selected segment's plane, keeping the side the view is on.
void Viewer::clipAtSelectedPlane() {
  const Segment* segment = theSelectedSegment("clip plane");
  if (!cloud_ || segment == nullptr || !clipFits(1, "clip plane")) return;
  const reco::Plane facing = segment->plane.orientedTowards(cloud_->navigator->camera().position);
  clip_.planes.push_back({facing.centroid, facing.normal.normalized()});
}

void Viewer::groupSelected() {
  const ecs::Entity group = scene_.groupSelected();
  const std::string message = group == ecs::kNullEntity ? "nothing selected to group"
                                                        : "grouped as " + scene_.registry().get<Group>(group).name;
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t.drawing.message = message; });
}

void Viewer::click(const PointerView& at) {
  const Tool tool = scene_.tool().active;
  if (tool == Tool::kNavigate) return selectAt(at);
  if (isDrawingTool(tool)) {
    drawing_.click(pointerAt(at, true), at.camera);
    return;
  }
  if (tool == Tool::kGrow) {
    const std::optional<Eigen::Vector3d> picked = at.pick ? at.pick(at.pixel.x(), at.pixel.y()) : std::nullopt;
    if (picked) startGrow(*picked, at.click_view);  // nothing on the background
    return;
  }
  measure_.click(at.camera, at.pixel.x(), at.pixel.y(), at.pick);
}

// The mouse's hover, unless the palette has it.
void Viewer::updateHover() {
  const bool over_view = cloud_ && !imgui_.wantsMouse();
  const std::optional<PointerView> at =
      over_view ? std::optional(mousePointer(mouse_x_ * renderScale(), mouse_y_ * renderScale())) : std::nullopt;
  hoverAt(at);
  if (at && isDrawingTool(scene_.tool().active)) hovered_px_ = at->pixel;
}

// In the Measure and drawing tools, what the pointer would snap to (features only: no readback
// of a frame), and the drawing tools' preview and direction.
void Viewer::hoverAt(const std::optional<PointerView>& at) {
  std::optional<Snap> hover;
  const Tool tool = scene_.tool().active;
  if (at && (tool == Tool::kMeasure || isDrawingTool(tool))) {
    const Pointer pointer = pointerAt(*at, false);
    hover = tool == Tool::kMeasure ? snapCursor(scene_.registry(), at->camera, at->pixel.x(), at->pixel.y(), nullptr,
                                                MeasureTool::snapOptionsFor(scene_.tool()))
                                   : pointer.snap;
    if (isDrawingTool(tool)) drawing_.hover(pointer, at->camera);
  }
  const std::optional<Snap>& now = scene_.tool().hover;
  const bool same = hover.has_value() == now.has_value() &&
                    (!hover || (hover->kind == now->kind && (hover->position - now->position).norm() < 1e-9));
  if (!same) scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& state) { state.hover = hover; });
}

// The grow parameters of a click at `picked` in `view` (the window's, or a headset eye's), with
// the panel's t_p and detail, the view's detail following `data` (the cloud at the click);
// nothing when the point lies behind the eye.
ClickView Viewer::desktopClickView() const {
  const view::Camera& camera = cloud_->navigator->camera();
  // The screen the user sees: the window, not the render's scaled viewport.
  return {camera, camera.viewport_width_px / renderScale(), camera.viewport_height_px / renderScale()};
}

std::optional<reco::GrowParameters> Viewer::clickParameters(const Eigen::Vector3d& picked,
                                                            const std::optional<reco::DataAtClick>& data,
                                                            const ClickView& screen) const {
  const std::optional<reco::ViewAtClick> view = viewAtClick(screen.camera, picked, screen.width_px, screen.height_px);
  if (!view) return std::nullopt;
  reco::ParameterConstants constants;
  constants.plane_threshold_m = grow_panel_.plane_threshold_m;
  constants.plane_threshold_from_data = grow_panel_.threshold_from_data;
  reco::GrowParameters parameters =
      reco::parametersForView(*view, constants, grow_panel_.detail == 0 ? data : std::nullopt);
  if (grow_panel_.detail >= 2) {
    const lod::Octree& octree = *cloud_->octree;
    const double density = reco::densityForDetail(static_cast<reco::Detail>(grow_panel_.detail - 2), constants,
                                                  std::pow(octree.spacing(octree.header().depth), -3.0));
    parameters = reco::parametersForDensity(picked, density, parameters.seed_radius_m, constants);
  }
  return parameters;
}

void Viewer::startGrow(const Eigen::Vector3d& picked, const ClickView& view) {
  // The data's spacing where the user clicked, for the view's detail (a few nodes, most of them
  // loaded for the picture already).
  if (grow_panel_.detail == 0) grow_panel_.last_data = reco::dataAtClick(*cloud_->cache, picked);
  const std::optional<reco::GrowParameters> parameters = clickParameters(picked, grow_panel_.last_data, view);
  if (!parameters) return;
  // Cancel first: the old grow's live outline goes now, and its late snapshots are dropped.
  scene_.dropLive();
  reco::GrowOptions options;
  if (grow_panel_.inside_section && clip_.active()) {
    options.keep = [spaces = clip_.region().halfSpaces()](const Eigen::Vector3d& p) { return spaces.keeps(p); };
  }
  cloud_->grow->start(*parameters, std::move(options));
  grow_panel_.last = parameters;
  grow_panel_.last_update.reset();
}

void Viewer::setTool(Tool tool) {
  drawing_.reset();
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& state) {
    state.active = tool;
    if (tool != Tool::kMeasure) forgetMeasureTerms(state);
    state.hover.reset();
  });
}

void Viewer::undo() {
  scene_.history().undo();
}

void Viewer::redo() {
  scene_.history().redo();
}

void Viewer::deleteSelected() {
  scene_.deleteSelected();
}

}  // namespace plumb::viewer
