// The palette: tools, the grow parameters, the segment list, view settings and the status bar.
// Dear ImGui is immediate: each frame draws it anew from the state, and a widget that changes
// something calls the viewer's action for it (setTool, undo, ...), never the ECS directly.

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cad/measurement.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/render/palette.h"
#include "engine/view/camera_controls.h"
#include "ui/viewer/project_bridge.h"
#include "ui/viewer/viewer.h"

namespace plumb::viewer {
namespace {

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// In the order of render::ColourMode, up to kScan.
const char* kColourModes[] = {"Auto", "RGB", "Intensity", "Elevation", "Scan"};
const char* kDetails[] = {"From the view",     "From the view, paper's densities", "Low", "Medium", "High",
                          "Full (every point)"};

}  // namespace

// The panels stand in two columns, each below the one before it (their sizes follow what they
// show), the tools and the grow parameters on the left, the scene, the view and the project on
// the right.
void Viewer::placeInColumn(bool right) {
  const VkExtent2D size = window_.framebufferSize();
  float& next_y = right ? right_column_y_ : left_column_y_;
  const float x = right ? static_cast<float>(size.width) - 400.0f : 10.0f;
  ImGui::SetNextWindowPos(ImVec2(x, next_y), ImGuiCond_Always);
}

void Viewer::endInColumn(bool right) {
  float& next_y = right ? right_column_y_ : left_column_y_;
  next_y = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y + 8.0f;
  ImGui::End();
}

void Viewer::drawPanels() {
  left_column_y_ = right_column_y_ = 10.0f;
  drawToolsPanel();
  drawGrowPanel();
  drawSegmentsPanel();
  drawMeasurementLabels();
  drawViewPanel();
  drawProjectPanel();
  drawStatusBar();
}

void Viewer::drawProjectPanel() {
  placeInColumn(true);
  ImGui::Begin("Project", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const bool unsaved = project_.unsaved(documentState());
  ImGui::Text("%s%s", std::filesystem::path(project_.path()).filename().string().c_str(), unsaved ? " *" : "");
  tooltip(project_.path().c_str());
  if (ImGui::Button("Save")) saveProject();
  tooltip(
      "Save the project (Ctrl+S); unsaved changes also go to an autosave beside it (every 30 s unless "
      "--autosave-s says otherwise)");
  ImGui::SameLine();
  if (ImGui::Button("Export")) exportProject();
  tooltip("Write glTF (.glb), OBJ, DXF and CSVs of the corners and the measurements beside the project (Ctrl+E)");
  if (!project_message_.empty()) ImGui::TextWrapped("%s", project_message_.c_str());
  endInColumn(true);
}

void Viewer::drawToolsPanel() {
  placeInColumn(false);
  ImGui::Begin("Tools", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const Tool active = scene_.tool().active;
  struct Entry {
    Tool tool;
    const char* name;
    const char* help;
  };
  static constexpr Entry kTools[] = {
      {Tool::kNavigate, "Navigate", "Orbit, pan, zoom; a click selects a segment or polygon, Ctrl+click adds (N)"},
      {Tool::kGrow, "Grow", "Click a surface: the planes around it grow at the detail the view shows (G)"},
      {Tool::kMeasure, "Measure",
       "Distances, angles, heights, a room's width, areas: choose the kind, then click what it asks for (M)"},
      {Tool::kPolygon, "Polygon",
       "Click snapped vertices; the first again, or Enter, closes. R: a rectangle from three points (P)"},
      {Tool::kMove, "Move/Copy",
       "Click a polygon, a base point, then where it goes; C toggles Copy. Hold Shift to lock the direction; "
       "type a distance and Enter (V)"},
      {Tool::kExtrude, "Extrude",
       "Click a polygon, then where its top face goes: a closed prism. Hold Shift to lock a direction found "
       "by pointing; type a distance and Enter (E)"},
  };
  for (const Entry& entry : kTools) {
    if (ImGui::RadioButton(entry.name, active == entry.tool)) setTool(entry.tool);
    tooltip(entry.help);
  }
  ImGui::Separator();
  ImGui::BeginDisabled(!scene_.history().canUndo());
  if (ImGui::Button("Undo")) undo();
  ImGui::EndDisabled();
  tooltip(scene_.history().canUndo() ? ("Undo " + std::string(scene_.history().undoName()) + " (Ctrl+Z)").c_str()
                                     : "Nothing to undo (Ctrl+Z)");
  ImGui::SameLine();
  ImGui::BeginDisabled(!scene_.history().canRedo());
  if (ImGui::Button("Redo")) redo();
  ImGui::EndDisabled();
  tooltip("Redo (Ctrl+Y)");
  ImGui::SameLine();
  if (ImGui::Button("Delete")) deleteSelected();
  tooltip("Delete the selected items; a segment takes its edges and corners (Delete)");
  if (ImGui::Button("Corner of 3")) cornerOfSelected();
  tooltip("A corner where the three selected segments meet, even with no points near it (K)");
  ImGui::SameLine();
  if (ImGui::Button("Group")) groupSelected();
  tooltip("Put the selected items in a new group (Ctrl+G)");
  ImGui::SameLine();
  if (ImGui::Button("Ungroup")) scene_.ungroupSelected();
  tooltip("Take the selected items out of their groups");
  const ToolState& tool = scene_.tool();
  if (tool.active == Tool::kPolygon || tool.active == Tool::kMove || tool.active == Tool::kExtrude) {
    drawDrawingToolState();
  }
  if (tool.active == Tool::kMeasure) drawMeasureToolState();
  endInColumn(false);
}

// The Measure tool's kinds, the next step and what it last measured.
void Viewer::drawMeasureToolState() {
  const ToolState& tool = scene_.tool();
  struct Entry {
    cad::MeasureKind kind;
    const char* help;
  };
  static constexpr Entry kKinds[] = {
      {cad::MeasureKind::kDistance, "From a corner, an edge, a plane or a point to another"},
      {cad::MeasureKind::kAngle, "Between two planes or edges, 0 to 90 degrees"},
      {cad::MeasureKind::kPointToPlane, "A plane, then points: each one's distance to it"},
      {cad::MeasureKind::kBetweenPlanes, "Two parallel planes (within 5 degrees): a room's width, a wall's thickness"},
      {cad::MeasureKind::kHeight, "A floor, then points: each one's height above it, vertically"},
      {cad::MeasureKind::kArea, "A drawn polygon: its area and perimeter"},
  };
  for (std::size_t i = 0; i < std::size(kKinds); ++i) {
    if (i % 3 != 0) ImGui::SameLine();
    if (ImGui::RadioButton(cad::measureKindTitle(kKinds[i].kind), tool.measure_kind == kKinds[i].kind)) {
      measure_.setKind(kKinds[i].kind);
    }
    tooltip(kKinds[i].help);
  }
  ImGui::TextUnformatted(MeasureTool::prompt(tool).c_str());
  if (!tool.measure_message.empty()) ImGui::TextWrapped("%s", tool.measure_message.c_str());
  if (tool.hover) ImGui::Text("under the cursor: %s", snapKindName(tool.hover->kind));
}

// Each measurement's value beside the middle of its dimension line, in the view; a label that
// would cover one placed before it moves down below it (a height and the room's height between
// floor and ceiling are often taken on one vertical).
void Viewer::drawMeasurementLabels() {
  if (!cloud_) return;
  const view::Camera& camera = cloud_->navigator->camera();
  const double scale = renderScale();
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  std::vector<std::pair<ImVec2, ImVec2>> placed;  // the labels' boxes so far
  const auto overlaps = [&](const ImVec2& min, const ImVec2& max) {
    return std::any_of(placed.begin(), placed.end(), [&](const auto& box) {
      return min.x < box.second.x && box.first.x < max.x && min.y < box.second.y && box.first.y < max.y;
    });
  };
  scene_.registry().view<Measurement>().each([&](ecs::Entity entity, const Measurement& measurement) {
    const cad::MeasureValue value = cad::measure(measurement.kind, measurement.terms);
    const std::optional<Eigen::Vector2d> pixel = view::pixelOf(camera, 0.5 * (value.from + value.to));
    if (!pixel) return;
    const std::string text = measurement.name + "  " + cad::measureText(measurement.kind, value);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    ImVec2 min(static_cast<float>(pixel->x() / scale) + 6.0f, static_cast<float>(pixel->y() / scale) - size.y - 4.0f);
    ImVec2 max(min.x + size.x + 6.0f, min.y + size.y + 4.0f);
    for (int tries = 0; tries < 8 && overlaps(min, max); ++tries) {
      min.y += size.y + 6.0f;
      max.y += size.y + 6.0f;
    }
    placed.emplace_back(min, max);
    const bool selected = scene_.registry().has<Selection>(entity);
    draw->AddRectFilled(min, max, selected ? IM_COL32(90, 90, 90, 220) : IM_COL32(0, 0, 0, 180), 3.0f);
    draw->AddText(ImVec2(min.x + 3.0f, min.y + 2.0f),
                  selected ? IM_COL32(255, 255, 255, 255) : IM_COL32(255, 200, 40, 255), text.c_str());
  });
}

// The drawing tool's options and what it says: the next step, the direction, a typed distance.
void Viewer::drawDrawingToolState() {
  const ToolState& tool = scene_.tool();
  const DrawingState& d = tool.drawing;
  if (tool.active == Tool::kPolygon) {
    bool rectangle = d.rectangle;
    if (ImGui::Checkbox("Rectangle from three points", &rectangle)) {
      scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t.drawing.rectangle = rectangle; });
    }
    tooltip("Two clicks give one side, the third the opposite side (R)");
  }
  if (tool.active == Tool::kMove) {
    bool copy = d.copy;
    if (ImGui::Checkbox("Copy", &copy)) {
      scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t.drawing.copy = copy; });
    }
    tooltip("Leave the original where it is; each click makes a copy from the last (C)");
  }
  if (!d.message.empty()) ImGui::TextWrapped("%s", d.message.c_str());
  if (d.direction) {
    ImGui::Text("direction %s: (%.3f, %.3f, %.3f)%s", d.direction->source, d.direction->vector.x(),
                d.direction->vector.y(), d.direction->vector.z(), d.direction_locked ? " LOCKED" : "");
  }
  ImGui::TextDisabled("hold Shift to lock the direction");
  if (!d.typed.empty()) ImGui::Text("distance: %s m (Enter)", d.typed.c_str());
  if (tool.hover) ImGui::Text("under the cursor: %s", snapKindName(tool.hover->kind));
}

void Viewer::drawGrowPanel() {
  placeInColumn(false);
  ImGui::Begin("Grow", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Checkbox("t_p from the data", &grow_panel_.threshold_from_data);
  tooltip("Each click measures the noise of the surfaces it seeds on; t_p is 3 x that where more than 0.02 m.");
  ImGui::BeginDisabled(grow_panel_.threshold_from_data);
  ImGui::SliderFloat("t_p (m)", &grow_panel_.plane_threshold_m, 0.001f, 0.1f, "%.3f", ImGuiSliderFlags_Logarithmic);
  tooltip("The plane threshold: how far a point may lie off its plane. Set it near 3 x the scanner's noise.");
  ImGui::EndDisabled();
  ImGui::Combo("Detail", &grow_panel_.detail, kDetails, IM_ARRAYSIZE(kDetails));
  tooltip(
      "From the view: nearer views grow finer, down to every point where a pixel is as fine as the points are "
      "apart. With the paper's densities: never finer than 4.6 cm, fast on dense scans. The others override the "
      "density the view implies.");
  ImGui::BeginDisabled(!clip_.active());
  ImGui::Checkbox("Inside the section only", &grow_panel_.inside_section);
  ImGui::EndDisabled();
  tooltip("Grows take only the points the slice and the clip box keep (the View panel's section)");
  // Live: what a click at the view's centre would use now (the target's depth, the data as the
  // last click measured it); then the last click's.
  if (cloud_) {
    if (const std::optional<reco::GrowParameters> now =
            clickParameters(cloud_->navigator->camera().target, grow_panel_.last_data, desktopClickView())) {
      ImGui::TextDisabled("at the view's centre now:");
      ImGui::Text("r_s %.3f m   d %.0f pts/m^3   r %.4f m", now->seed_radius_m, now->density, now->search_radius_m);
    }
  }
  if (grow_panel_.last) {
    const reco::GrowParameters& p = *grow_panel_.last;
    ImGui::TextDisabled("the last click:");
    ImGui::Text("r_s %.3f m   d %.0f pts/m^3", p.seed_radius_m, p.density);
    ImGui::Text("r %.4f m", p.search_radius_m);
    if (p.click_spacing_m > 0.0) {
      ImGui::Text("pixel %.2f mm at the click, points %.1f mm apart", p.pixel_size_m * 1e3, p.click_spacing_m * 1e3);
    } else {
      ImGui::Text("pixel %.2f mm at the click", p.pixel_size_m * 1e3);
    }
  } else {
    ImGui::TextUnformatted("Click a surface with the Grow tool (G).");
  }
  if (grow_panel_.last_update) {
    const GrowUpdate& u = *grow_panel_.last_update;
    const reco::GrowSnapshot& s = u.snapshot;
    ImGui::Text("%s: %zu segments, %zu edges, %zu corners",
                s.cancelled ? "cancelled" : (u.final ? "converged" : "growing"), s.segments.size(), s.edges.size(),
                s.corners.size());
    ImGui::Text("first snapshot %.1f ms, %s %.1f ms", u.first_progress_ms, u.final ? "done" : "now", s.elapsed_ms);
    ImGui::Text("cells %" PRIu64 ", points tested %" PRIu64, s.cells_visited, s.points_tested);
    if (s.noise_sigma_m > 0.0) {
      ImGui::Text("t_p %.4f m in use (the noise measured: %.2f mm)", s.plane_threshold_m, s.noise_sigma_m * 1e3);
    } else {
      ImGui::Text("t_p %.4f m in use", s.plane_threshold_m);
    }
  }
  if (cloud_ && cloud_->grow && cloud_->grow->busy()) {
    if (ImGui::Button("Cancel")) cloud_->grow->cancel();
    tooltip("Stop the running grow (Escape)");
  }
  endInColumn(false);
}

void Viewer::drawSegmentsPanel() {
  ecs::Registry& registry = scene_.registry();
  placeInColumn(true);
  const bool polygons = registry.count<Polygon>() > 0;
  const bool measurements = registry.count<Measurement>() > 0;
  ImGui::SetNextWindowSize(ImVec2(390, 220.0f + (polygons ? 120.0f : 0.0f) + (measurements ? 120.0f : 0.0f)),
                           ImGuiCond_Always);
  ImGui::Begin("Segments", nullptr, ImGuiWindowFlags_NoResize);
  const auto group_name = [&](ecs::Entity entity) -> std::string {
    const InGroup* in = registry.tryGet<InGroup>(entity);
    const Group* group = in ? registry.tryGet<Group>(in->group) : nullptr;
    return group ? group->name : "";
  };
  std::vector<ecs::Entity> clicked;  // applied after the walk: no changes while viewing
  const auto row = [&](ecs::Entity entity, const std::string& name) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const std::string label = name + "##" + std::to_string(entity.id());
    if (ImGui::Selectable(label.c_str(), registry.has<Selection>(entity), ImGuiSelectableFlags_SpanAllColumns)) {
      clicked.push_back(entity);
    }
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(group_name(entity).c_str());
  };
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_Borders;
  if (ImGui::BeginTable("segments", 5, flags, ImVec2(0, 150))) {
    ImGui::TableSetupColumn("Segment");
    ImGui::TableSetupColumn("Group");
    ImGui::TableSetupColumn("Points");
    ImGui::TableSetupColumn("Area m^2");
    ImGui::TableSetupColumn("lambda2 mm^2");
    ImGui::TableHeadersRow();
    registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
      row(entity, segment.growing ? std::string("(growing)") : segment.name);
      ImGui::TableNextColumn();
      ImGui::Text("%" PRIu64, segment.points);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", segment.area_m2);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", segment.lambda2 * 1e6);
    });
    ImGui::EndTable();
  }
  if (polygons && ImGui::BeginTable("polygons", 4, flags, ImVec2(0, 110))) {
    ImGui::TableSetupColumn("Polygon");
    ImGui::TableSetupColumn("Group");
    ImGui::TableSetupColumn("Vertices");
    ImGui::TableSetupColumn("Extruded m");
    ImGui::TableHeadersRow();
    registry.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
      row(entity, polygon.name);
      ImGui::TableNextColumn();
      ImGui::Text("%zu%s", polygon.vertices.size(), polygon.plane != ecs::kNullEntity ? " on a plane" : "");
      ImGui::TableNextColumn();
      if (!polygon.extrusion.isZero(0.0)) ImGui::Text("%.4f", polygon.extrusion.norm());
    });
    ImGui::EndTable();
  }
  if (measurements && ImGui::BeginTable("measurements", 3, flags, ImVec2(0, 110))) {
    ImGui::TableSetupColumn("Measurement", ImGuiTableColumnFlags_WidthFixed, 110.0f);
    ImGui::TableSetupColumn("Group", ImGuiTableColumnFlags_WidthFixed, 50.0f);
    ImGui::TableSetupColumn("Value", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    registry.view<Measurement>().each([&](ecs::Entity entity, const Measurement& measurement) {
      row(entity, measurement.name);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(
          cad::measureText(measurement.kind, cad::measure(measurement.kind, measurement.terms)).c_str());
    });
    ImGui::EndTable();
  }
  const bool extend = ImGui::GetIO().KeyCtrl;
  for (const ecs::Entity entity : clicked) scene_.select(entity, extend);
  // Renaming the one selected item.
  const std::vector<ecs::Entity> selected = scene_.selected();
  if (selected.size() == 1) {
    const ecs::Entity entity = selected.front();
    std::string name;
    if (const Segment* segment = registry.tryGet<Segment>(entity)) name = segment->name;
    if (const Polygon* polygon = registry.tryGet<Polygon>(entity)) name = polygon->name;
    if (const Measurement* measurement = registry.tryGet<Measurement>(entity)) name = measurement->name;
    const InGroup* in = registry.tryGet<InGroup>(entity);
    if (rename_entity_ != entity) {
      rename_entity_ = entity;
      std::snprintf(rename_buffer_, sizeof rename_buffer_, "%s", name.c_str());
    }
    if (ImGui::InputText("Name", rename_buffer_, sizeof rename_buffer_, ImGuiInputTextFlags_EnterReturnsTrue) &&
        name != rename_buffer_) {
      scene_.rename(entity, rename_buffer_);
    }
    tooltip("Type a name and press Enter");
    if (in && registry.has<Group>(in->group)) {
      if (group_entity_ != in->group) {
        group_entity_ = in->group;
        std::snprintf(group_buffer_, sizeof group_buffer_, "%s", registry.get<Group>(in->group).name.c_str());
      }
      if (ImGui::InputText("Group name", group_buffer_, sizeof group_buffer_, ImGuiInputTextFlags_EnterReturnsTrue)) {
        scene_.rename(in->group, group_buffer_);
      }
    }
  } else {
    rename_entity_ = group_entity_ = ecs::kNullEntity;
  }
  endInColumn(true);
}

void Viewer::drawViewPanel() {
  placeInColumn(true);
  ImGui::Begin("View", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  if (cloud_) {
    Navigator& navigator = *cloud_->navigator;
    if (ImGui::Button("Top")) navigator.showPreset(view::ViewPreset::kTop);
    tooltip("Orthographic, from above (1)");
    ImGui::SameLine();
    if (ImGui::Button("Front")) navigator.showPreset(view::ViewPreset::kFront);
    tooltip("Orthographic, along +y (2)");
    ImGui::SameLine();
    if (ImGui::Button("Side")) navigator.showPreset(view::ViewPreset::kSide);
    tooltip("Orthographic, along -x (3)");
    ImGui::SameLine();
    if (ImGui::Button("Iso")) navigator.showPreset(view::ViewPreset::kIso);
    tooltip("Perspective, from the front right above (4)");
    ImGui::SameLine();
    if (ImGui::Button("Home")) navigator.home();
    tooltip("The first view (H)");
    ImGui::SameLine();
    if (ImGui::Button("Elevation")) showElevationOfSelected();
    tooltip("Orthographic, straight at the selected segment's plane: a facade's elevation, a floor's plan");
    bool ortho = navigator.camera().projection == view::Projection::kOrthographic;
    if (ImGui::Checkbox("Orthographic", &ortho)) navigator.toggleOrthographic();
    tooltip("Perspective or orthographic (O)");
    ImGui::SameLine();
    bool fly = navigator.flying();
    if (ImGui::Checkbox("Fly", &fly)) navigator.toggleFly();
    tooltip("W A S D to move, Q E down and up, drag to look, Shift faster, wheel for speed (F)");
  }
  drawHeadsetControls();
  int budget_k = static_cast<int>(settings_.selection.point_budget / 1000);
  if (ImGui::SliderInt("Budget (k points)", &budget_k, 100, 20000, "%d", ImGuiSliderFlags_Logarithmic)) {
    settings_.selection.point_budget = static_cast<std::uint64_t>(budget_k) * 1000;
  }
  tooltip("The most points a frame draws; fewer is faster");
  if (ImGui::SliderFloat("Render scale", &render_scale_, 0.25f, 1.0f, "%.2f")) moving_scale_ = render_scale_;
  tooltip("The resolution the cloud renders at, against the window's");
  ImGui::Checkbox("Faster while moving", &adaptive_quality_);
  tooltip(
      "While the view moves, render fewer pixels and points to keep 30 frames per second; a still view is "
      "drawn in full");
  if (adaptive_quality_) {
    ImGui::SameLine();
    ImGui::Text("(moving: scale %.2f)", moving_scale_);
  }
  int colour = static_cast<int>(settings_.colour);
  if (colour >= IM_ARRAYSIZE(kColourModes)) colour = 0;
  if (ImGui::Combo("Colour", &colour, kColourModes, IM_ARRAYSIZE(kColourModes))) {
    settings_.colour = static_cast<render::ColourMode>(colour);
  }
  tooltip("Scan: a colour per scan of a cloud that merges several (E57 scans, or several files imported together)");
  if (settings_.colour == render::ColourMode::kScan && cloud_) drawScanLegend();
  if (cloud_) drawSectionControls();
  ImGui::Checkbox("Eye-dome lighting", &settings_.edl);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  ImGui::SliderFloat("##edl", &settings_.edl_strength, 0.05f, 1.5f, "%.2f");
  tooltip("Shading from depth differences: edges and steps stand out");
  ImGui::Separator();
  ImGui::Text("%.1f ms per frame (%.0f fps)", frame_ms_avg_, frame_ms_avg_ > 0 ? 1e3 / frame_ms_avg_ : 0.0);
  ImGui::Text("%" PRIu64 " points in %" PRIu64 " nodes, %" PRIu64 " to load", last_stats_.points_drawn,
              last_stats_.nodes_drawn, last_stats_.nodes_missing);
  endInColumn(true);
}

// The section: a horizontal slice (stepped with Page Up and Page Down) and a clip box; what they
// cut away is neither drawn nor picked.
void Viewer::drawSectionControls() {
  ImGui::Separator();
  const lod::Box3& bounds = cloud_->octree->header().bounds;
  bool slice = clip_.slice;
  if (ImGui::Checkbox("Slice", &slice) && (!slice || clipFits(2, "slice"))) {
    // A new slice starts at the height the view looks at.
    if (slice) clip_.slice_bottom_z = cloud_->navigator->camera().target.z() - 0.5 * clip_.slice_thickness;
    clip_.slice = slice;
  }
  tooltip("Keep a horizontal band of the cloud; Page Up and Page Down step it by its thickness");
  if (clip_.slice) {
    ImGui::SameLine();
    if (ImGui::Button("Plan")) cloud_->navigator->showPreset(view::ViewPreset::kTop);
    tooltip("Orthographic, from above: the slice as a plan");
    const double low = bounds.min[2] - 1.0, high = bounds.max[2] + 1.0, thin = 0.005, thick = 10.0;
    ImGui::DragScalar("Bottom (m)", ImGuiDataType_Double, &clip_.slice_bottom_z, 0.01f, &low, &high, "%.3f");
    ImGui::DragScalar("Thickness (m)", ImGuiDataType_Double, &clip_.slice_thickness, 0.005f, &thin, &thick, "%.3f",
                      ImGuiSliderFlags_AlwaysClamp);
  }
  bool slab = clip_.slab.has_value();
  if (ImGui::Checkbox("Slab", &slab) && (!slab || clip_.slab || clipFits(2, "slab"))) {
    clip_.slab.reset();
    if (slab) {
      if (const Segment* segment = theSelectedSegment("slab")) {
        clip_.slab = view::ClipSlab{segment->plane.centroid, segment->plane.normal.normalized(), 0.2};
      }
    }
  }
  tooltip(
      "Keep a slab about the selected segment's plane (a facade's section, with Elevation); Page Up and Page Down "
      "step it along the plane's normal when no slice is on");
  if (clip_.slab) {
    const double thin = 0.005, thick = 10.0;
    ImGui::DragScalar("Slab thickness (m)", ImGuiDataType_Double, &clip_.slab->thickness, 0.005f, &thin, &thick, "%.3f",
                      ImGuiSliderFlags_AlwaysClamp);
  }
  bool box = clip_.box.has_value();
  if (ImGui::Checkbox("Clip box", &box) && (!box || clipFits(6, "clip box"))) {
    // A new box holds the cloud's bulk (its framing box, without stray points): shrink it from there.
    if (box) {
      const lod::Box3& framing = cloud_->framing;
      view::ClipBox whole;
      for (std::size_t a = 0; a < 3; ++a) {
        whole.centre[static_cast<Eigen::Index>(a)] = 0.5 * (framing.min[a] + framing.max[a]);
        whole.half_size[static_cast<Eigen::Index>(a)] = std::max(0.5 * (framing.max[a] - framing.min[a]), 0.05);
      }
      clip_.box = whole;
    } else {
      clip_.box.reset();
    }
  }
  tooltip("Keep the points inside a box (or outside it)");
  if (clip_.box) {
    ImGui::SameLine();
    ImGui::Checkbox("Keep outside", &clip_.keep_outside_box);
    view::ClipBox& b = *clip_.box;
    ImGui::DragScalarN("Centre", ImGuiDataType_Double, b.centre.data(), 3, 0.02f, nullptr, nullptr, "%.2f");
    Eigen::Vector3d size = 2.0 * b.half_size;
    const double smallest = 0.01, largest = 1e6;
    if (ImGui::DragScalarN("Size", ImGuiDataType_Double, size.data(), 3, 0.02f, &smallest, &largest, "%.2f",
                           ImGuiSliderFlags_AlwaysClamp)) {
      b.half_size = 0.5 * size.cwiseMax(smallest);
    }
    double yaw_deg = b.yaw_rad * 180.0 / M_PI;
    const double turn_low = -180.0, turn_high = 180.0;
    if (ImGui::DragScalar("Turn (deg)", ImGuiDataType_Double, &yaw_deg, 0.5f, &turn_low, &turn_high, "%.1f",
                          ImGuiSliderFlags_AlwaysClamp)) {
      b.yaw_rad = yaw_deg * M_PI / 180.0;
    }
    ImGui::TextDisabled("or drag its handles (Shift: the centre up, down)");
  }
  drawClipPlaneControls();
}

// Clip planes: each keeps one side of a selected segment's plane, the side the view is on.
void Viewer::drawClipPlaneControls() {
  if (ImGui::Button("Clip at plane")) clipAtSelectedPlane();
  tooltip("Keep the side of the selected segment's plane that the view is on: a wall cut away to see the room (X)");
  std::optional<std::size_t> removed;
  for (std::size_t i = 0; i < clip_.planes.size(); ++i) {
    view::ClipPlane& plane = clip_.planes[i];
    ImGui::PushID(static_cast<int>(i));
    ImGui::Text("Plane %zu: normal (%.2f, %.2f, %.2f)", i + 1, plane.normal.x(), plane.normal.y(), plane.normal.z());
    ImGui::SameLine();
    if (ImGui::SmallButton("Flip")) plane.normal = -plane.normal;
    tooltip("Keep the other side");
    ImGui::SameLine();
    if (ImGui::SmallButton("Remove")) removed = i;
    ImGui::PopID();
  }
  if (removed) clip_.planes.erase(clip_.planes.begin() + static_cast<std::ptrdiff_t>(*removed));
}

// The scans' colours and names; a long list scrolls.
void Viewer::drawScanLegend() {
  const std::vector<std::string>& scans = cloud_->octree->header().scans;
  if (scans.empty()) {
    ImGui::TextDisabled("One scan: every point has its colour");
    return;
  }
  ImGui::Text("%zu scans", scans.size());
  const float rows = static_cast<float>(std::min<std::size_t>(scans.size(), 8));
  ImGui::BeginChild("scans", ImVec2(0, rows * ImGui::GetTextLineHeightWithSpacing() + 4), false);
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(scans.size()));
  while (clipper.Step()) {
    for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
      const std::array<float, 3> rgb = render::scanColour(static_cast<std::uint32_t>(i));
      ImGui::ColorButton(("##scan" + std::to_string(i)).c_str(), ImVec4(rgb[0], rgb[1], rgb[2], 1.0f),
                         ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
      ImGui::SameLine();
      ImGui::TextUnformatted(scans[static_cast<std::size_t>(i)].c_str());
    }
  }
  ImGui::EndChild();
}

void Viewer::drawStatusBar() {
  const VkExtent2D size = window_.framebufferSize();
  const float height = ImGui::GetFrameHeight() + 8;
  ImGui::SetNextWindowPos(ImVec2(0, static_cast<float>(size.height) - height));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(size.width), height));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus);
  if (!cloud_) {
    const std::scoped_lock lock(load_progress_->mutex);
    if (load_progress_->error) {
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", load_progress_->error->c_str());
    } else {
      ImGui::ProgressBar(static_cast<float>(load_progress_->fraction), ImVec2(240, 0));
      ImGui::SameLine();
      ImGui::TextUnformatted(load_progress_->phase.c_str());
    }
  } else {
    const bool growing = cloud_->grow && cloud_->grow->busy();
    ImGui::Text("%s | %s | %zu segments, %zu polygons | %s", toolName(scene_.tool().active),
                growing ? "growing..." : "ready", scene_.registry().count<Segment>(),
                scene_.registry().count<Polygon>(), last_stats_.complete() ? "all nodes loaded" : "streaming");
    const lod::NodeCacheStats cache = cloud_->cache->stats();
    ImGui::SameLine();
    ImGui::Text("| cache %.0f MB | %.0f fps", static_cast<double>(cache.bytes) / 1e6,
                frame_ms_avg_ > 0 ? 1e3 / frame_ms_avg_ : 0.0);
    // A preview is shown while the whole file is imported (or failed to).
    const std::scoped_lock lock(load_progress_->mutex);
    if (load_progress_->error) {
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "| preview only: %s", load_progress_->error->c_str());
    } else if (!load_progress_->finished) {
      ImGui::SameLine();
      ImGui::TextUnformatted("| preview;");
      ImGui::SameLine();
      ImGui::ProgressBar(static_cast<float>(load_progress_->fraction), ImVec2(160, 0));
      ImGui::SameLine();
      ImGui::TextUnformatted(load_progress_->phase.c_str());
    }
  }
  ImGui::End();
}

}  // namespace plumb::viewer
