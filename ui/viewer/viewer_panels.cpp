// The palette: tools, the grow parameters, the segment list, view settings and the status bar.
// Dear ImGui is immediate: each frame draws it anew from the state, and a widget that changes
// something calls the viewer's action for it (setTool, undo, ...), never the ECS directly.

#include <imgui.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "ui/viewer/viewer.h"

namespace plumb::viewer {
namespace {

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

const char* kColourModes[] = {"Auto", "RGB", "Intensity", "Elevation"};
const char* kDetails[] = {"From the view", "Low", "Medium", "High", "Full (every point)"};

}  // namespace

void Viewer::drawPanels() {
  drawToolsPanel();
  drawGrowPanel();
  drawSegmentsPanel();
  drawViewPanel();
  drawStatusBar();
}

void Viewer::drawToolsPanel() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tools", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const Tool active = scene_.tool().active;
  struct Entry {
    Tool tool;
    const char* name;
    const char* help;
  };
  static constexpr Entry kTools[] = {
      {Tool::kNavigate, "Navigate", "Orbit, pan, zoom; clicks do nothing (N)"},
      {Tool::kGrow, "Grow", "Click a surface: the planes around it grow at the detail the view shows (G)"},
      {Tool::kMeasure, "Measure", "Click two points: their distance (M)"},
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
  tooltip("Delete the selected segments with their edges and corners (Delete)");
  const ToolState& tool = scene_.tool();
  if (tool.active == Tool::kMeasure) {
    if (tool.measure_done) {
      ImGui::Text("Distance %.4f m (%s to %s)", (tool.measure_to - tool.measure_from).norm(),
                  snapKindName(tool.measure_from_kind), snapKindName(tool.measure_to_kind));
    } else {
      ImGui::TextUnformatted(tool.measure_started ? "Click the second point" : "Click the first point");
    }
    ImGui::TextDisabled("snaps to corners, edges, planes, points");
    if (tool.hover) ImGui::Text("under the cursor: %s", snapKindName(tool.hover->kind));
  }
  ImGui::End();
}

void Viewer::drawGrowPanel() {
  ImGui::SetNextWindowPos(ImVec2(10, 190), ImGuiCond_FirstUseEver);
  ImGui::Begin("Grow", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::SliderFloat("t_p (m)", &grow_panel_.plane_threshold_m, 0.001f, 0.1f, "%.3f", ImGuiSliderFlags_Logarithmic);
  tooltip("The plane threshold: how far a point may lie off its plane. Set it near 3 x the scanner's noise.");
  ImGui::Combo("Detail", &grow_panel_.detail, kDetails, IM_ARRAYSIZE(kDetails));
  tooltip("From the view: nearer views grow finer. The others override the density the view implies.");
  // Live: what a click at the view's centre would use now (the target's depth); then the
  // last click's.
  if (cloud_) {
    if (const std::optional<reco::GrowParameters> now = clickParameters(cloud_->navigator->camera().target)) {
      ImGui::TextDisabled("at the view's centre now:");
      ImGui::Text("r_s %.3f m   d %.0f pts/m^3   r %.4f m", now->seed_radius_m, now->density, now->search_radius_m);
    }
  }
  if (grow_panel_.last) {
    const reco::GrowParameters& p = *grow_panel_.last;
    ImGui::TextDisabled("the last click:");
    ImGui::Text("r_s %.3f m   d %.0f pts/m^3", p.seed_radius_m, p.density);
    ImGui::Text("r %.4f m   t_p %.4f m", p.search_radius_m, p.plane_threshold_m);
    ImGui::Text("pixel %.2f mm at the click", p.pixel_size_m * 1e3);
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
  }
  if (cloud_ && cloud_->grow && cloud_->grow->busy()) {
    if (ImGui::Button("Cancel")) cloud_->grow->cancel();
    tooltip("Stop the running grow (Escape)");
  }
  ImGui::End();
}

void Viewer::drawSegmentsPanel() {
  const VkExtent2D size = window_.framebufferSize();
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(size.width) - 400, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(390, 220), ImGuiCond_FirstUseEver);
  ImGui::Begin("Segments");
  ecs::Registry& registry = scene_.registry();
  if (ImGui::BeginTable("segments", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_Borders)) {
    ImGui::TableSetupColumn("Name");
    ImGui::TableSetupColumn("Points");
    ImGui::TableSetupColumn("Area m^2");
    ImGui::TableSetupColumn("lambda2 mm^2");
    ImGui::TableHeadersRow();
    std::vector<std::pair<ecs::Entity, bool>> clicked;  // applied after the walk: no changes while viewing
    registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const bool selected = registry.has<Selection>(entity);
      const std::string label =
          (segment.growing ? std::string("(growing)") : segment.name) + "##" + std::to_string(entity.id());
      if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_SpanAllColumns)) {
        clicked.emplace_back(entity, selected);
      }
      ImGui::TableNextColumn();
      ImGui::Text("%" PRIu64, segment.points);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", segment.area_m2);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", segment.lambda2 * 1e6);
    });
    ImGui::EndTable();
    const bool extend = ImGui::GetIO().KeyCtrl;
    for (const auto& [entity, was_selected] : clicked) {
      if (!extend) {
        std::vector<ecs::Entity> others;
        registry.view<Selection>().each([&](ecs::Entity e, const Selection&) { others.push_back(e); });
        for (const ecs::Entity e : others) registry.remove<Selection>(e);
      }
      if (was_selected && extend) {
        registry.remove<Selection>(entity);
      } else {
        registry.emplaceOrReplace(entity, Selection{});
      }
    }
  }
  ImGui::End();
}

void Viewer::drawViewPanel() {
  const VkExtent2D size = window_.framebufferSize();
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(size.width) - 400, 240), ImGuiCond_FirstUseEver);
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
    bool ortho = navigator.camera().projection == view::Projection::kOrthographic;
    if (ImGui::Checkbox("Orthographic", &ortho)) navigator.toggleOrthographic();
    tooltip("Perspective or orthographic (O)");
    ImGui::SameLine();
    bool fly = navigator.flying();
    if (ImGui::Checkbox("Fly", &fly)) navigator.toggleFly();
    tooltip("W A S D to move, Q E down and up, drag to look, Shift faster, wheel for speed (F)");
  }
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
  if (colour > 3) colour = 0;
  if (ImGui::Combo("Colour", &colour, kColourModes, IM_ARRAYSIZE(kColourModes))) {
    settings_.colour = static_cast<render::ColourMode>(colour);
  }
  ImGui::Checkbox("Eye-dome lighting", &settings_.edl);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  ImGui::SliderFloat("##edl", &settings_.edl_strength, 0.05f, 1.5f, "%.2f");
  tooltip("Shading from depth differences: edges and steps stand out");
  ImGui::Separator();
  ImGui::Text("%.1f ms per frame (%.0f fps)", frame_ms_avg_, frame_ms_avg_ > 0 ? 1e3 / frame_ms_avg_ : 0.0);
  ImGui::Text("%" PRIu64 " points in %" PRIu64 " nodes, %" PRIu64 " to load", last_stats_.points_drawn,
              last_stats_.nodes_drawn, last_stats_.nodes_missing);
  ImGui::End();
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
    ImGui::Text("%s | %s | %zu segments | %s",
                scene_.tool().active == Tool::kGrow      ? "Grow"
                : scene_.tool().active == Tool::kMeasure ? "Measure"
                                                         : "Navigate",
                growing ? "growing..." : "ready", scene_.registry().count<Segment>(),
                last_stats_.complete() ? "all nodes loaded" : "streaming");
    const lod::NodeCacheStats cache = cloud_->cache->stats();
    ImGui::SameLine();
    ImGui::Text("| cache %.0f MB | %.0f fps", static_cast<double>(cache.bytes) / 1e6,
                frame_ms_avg_ > 0 ? 1e3 / frame_ms_avg_ : 0.0);
  }
  ImGui::End();
}

}  // namespace plumb::viewer
