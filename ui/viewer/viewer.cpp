#include "ui/viewer/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cad/export.h"
#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "engine/io/png_image.h"
#include "engine/io/sampled_reader.h"
#include "engine/lod/framing.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/lod/octree_builder.h"
#include "engine/view/camera_controls.h"
#include "reco/data_at_click.h"
#include "ui/viewer/demo_scan.h"
#include "ui/viewer/project_bridge.h"
#include "ui/viewer/snapping.h"
#include "ui/viewer/view_at_click.h"

namespace plumb::viewer {
namespace {

// A digest of what a project keeps of the section (its "section"), so that a changed section marks
// the project unsaved as an edit of the scene does.
std::uint64_t sectionDigest(const view::ClipSettings& clip) {
  if (!clip.active()) return 0;
  std::uint64_t digest = 14695981039346656037ull;  // FNV-1a over the values' bits
  const auto mix = [&](double value) { digest = (digest ^ std::bit_cast<std::uint64_t>(value)) * 1099511628211ull; };
  const auto mixVector = [&](const Eigen::Vector3d& v) {
    for (Eigen::Index i = 0; i < 3; ++i) mix(v[i]);
  };
  if (clip.slice) {
    mix(1.0);
    mix(clip.slice_bottom_z);
    mix(clip.slice_thickness);
  }
  if (clip.slab) {
    mix(2.0);
    mixVector(clip.slab->point);
    mixVector(clip.slab->normal);
    mix(clip.slab->thickness);
  }
  if (clip.box) {
    mix(clip.keep_outside_box ? 4.0 : 3.0);
    mixVector(clip.box->centre);
    mixVector(clip.box->half_size);
    mix(clip.box->yaw_rad);
  }
  for (const view::ClipPlane& plane : clip.planes) {
    mix(5.0);
    mixVector(plane.point);
    mixVector(plane.normal);
  }
  return digest;
}

// What a saved project holds, for the messages of saves and autosaves.
std::string projectContents(const cad::Project& project) {
  return std::to_string(project.segments.size()) + " segments, " + std::to_string(project.polygons.size()) +
         " polygons";
}

bool isDrawingTool(Tool tool) {
  return tool == Tool::kPolygon || tool == Tool::kMove || tool == Tool::kExtrude;
}

constexpr std::size_t kNodeCacheBytes = std::size_t{1} << 30;
constexpr std::uint64_t kPreviewPoints = 500'000;  // an import's preview holds about this many
constexpr double kMovingFrameMs = 1000.0 / 30.0;   // what a moving view aims for

gpu::DeviceChoice deviceChoice(const ViewerOptions& options, VkSurfaceKHR surface) {
  gpu::DeviceChoice choice =
      options.gpu.empty() ? gpu::deviceChoiceFromEnvironment() : gpu::DeviceChoice{.prefer = options.gpu};
  choice.present_to = surface;
  return choice;
}

}  // namespace

LoadedCloud::~LoadedCloud() {
  grow.reset();      // waits for a running grow
  renderer.reset();  // waits for the GPU
  cache.reset();     // waits for background loads
  octree.reset();
  if (!temporary.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  }
}

Viewer::Viewer(const ViewerOptions& options)
    : options_(options),
      project_(ProjectSession::open(options.project, options.cloud)),
      instance_(gpu::instanceOptionsFromEnvironment(), windows_.requiredInstanceExtensions()),
      window_(windows_, options.width, options.height, "Plumb"),
      surface_(window_.createSurface(instance_.handle())),
      device_(instance_, deviceChoice(options, surface_)),
      swapchain_(instance_, device_, surface_, [this] { return window_.framebufferSize(); }),
      allocator_(device_),
      imgui_(instance_, device_, swapchain_),
      screenshots_(device_, allocator_),
      ui_commands_(device_, "viewer interface"),
      ui_timeline_(device_) {
  // On the CPU (lavapipe) a frame costs about 135 ns per rendered pixel and 22 ns per point on
  // top of some 30 ms for a 1280 x 720 window (docs/benchmarks.md): a still view renders at half
  // the resolution and a million points; a moving one lowers both towards 30 frames per second.
  const bool cpu = device_.isCpu();
  render_scale_ = static_cast<float>(options.render_scale > 0.0 ? options.render_scale : (cpu ? 0.5 : 1.0));
  moving_scale_ = render_scale_;
  adaptive_quality_ = options.adaptive_quality;
  settings_.selection.point_budget = options.budget_points > 0 ? options.budget_points : (cpu ? 1'000'000 : 5'000'000);
  grow_panel_.plane_threshold_m = static_cast<float>(options.plane_threshold_m);
  clip_ = options.clip;
  grow_panel_.threshold_from_data = options.plane_threshold_from_data;
  jobs_.setWakeUp([] { Window::wakeUp(); });
  project_.setAutosaveInterval(std::chrono::milliseconds(std::lround(options.autosave_s * 1e3)));
  if (!options.script.empty()) {
    script_.emplace(readSessionScript(options.script),
                    options.script_wall_clock ? ScriptClock::kWall : ScriptClock::kScript);
  }
  openProject();
  startLoading();
}

Viewer::~Viewer() {
  // Unsaved changes into the autosave, however the session ended (an error out of run too).
  try {
    autosaveProject(true);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "plumb view: the autosave failed: %s\n", error.what());
  }
  if (cloud_ && cloud_->grow) cloud_->grow->cancel();
  jobs_.waitIdle();  // an import or a grow still running finishes (or sees its cancellation) first
  // The octrees an import made that the viewer never opened (it closed first): not left behind.
  // The one it shows goes with it.
  for (const std::string& temporary : load_progress_->temporaries) {
    if (cloud_ && cloud_->temporary == temporary) continue;
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  }
  cloud_.reset();
  vkDeviceWaitIdle(device_.handle());
}

// --- the project --------------------------------------------------------------------------------

// The project's items into the scene; its cloud and first view unless the command line gave them.
void Viewer::openProject() {
  std::optional<cad::Project> project = project_.takeOpened();
  if (!project) {
    project_.markSaved(documentState());
    return;
  }
  if (options_.cloud.empty() && !project->cloud_path.empty()) {
    const std::filesystem::path cloud = project->cloud_path;
    options_.cloud =
        cloud.is_absolute() ? cloud.string() : (std::filesystem::path(project_.path()).parent_path() / cloud).string();
  }
  if (!options_.camera && project->camera) options_.camera = project->camera;
  if (!options_.clip.active() && project->section) clip_ = *project->section;
  loadProject(*project, scene_);
  // Recovered work is not in the project file yet.
  project_.markSaved(project_.recovered() ? ~std::uint64_t{0} : documentState());
  project_message_ =
      project_.recovered() ? "recovered unsaved work from " + project_.autosavePath() : "opened " + project_.path();
  std::printf("plumb view: %s\n", project_message_.c_str());
}

cad::Project Viewer::currentProject() const {
  const std::string cloud = options_.cloud.empty() ? "" : std::filesystem::absolute(options_.cloud).string();
  std::optional<view::Camera> camera;
  camera = cloud_ ? std::optional(cloud_->navigator->camera()) : options_.camera;
  if (camera && view::findCameraProblem(*camera)) camera.reset();  // a project without a view beats none saved
  cad::Project project = projectOf(scene_.registry(), cloud, camera);
  if (clip_.active()) project.section = clip_;
  return project;
}

void Viewer::saveProject() {
  try {
    const cad::Project project = currentProject();
    project_.save(project, documentState());
    project_message_ = "saved " + project_.path() + " (" + projectContents(project) + ")";
  } catch (const std::exception& error) {
    project_message_ = error.what();
  }
  std::printf("plumb view: %s\n", project_message_.c_str());
  std::fflush(stdout);  // the line tells what is safe on disk, even to the log of a killed session
}

// Unsaved changes go to the autosave every autosave interval (--autosave-s), and when the viewer
// closes (`now`).
void Viewer::autosaveProject(bool now) {
  const std::uint64_t version = documentState();
  const Clock::time_point time = Clock::now();
  if (!(now ? project_.unsaved(version) : project_.autosaveDue(version, time))) return;
  try {
    const cad::Project project = currentProject();
    project_.autosave(project, version, time);
    std::printf("plumb view: %s %s (%s)\n", now ? "unsaved changes kept in" : "autosaved",
                project_.autosavePath().c_str(), projectContents(project).c_str());
    std::fflush(stdout);
  } catch (const std::exception& error) {
    project_message_ = std::string("autosave failed: ") + error.what();
    std::fprintf(stderr, "plumb view: %s\n", project_message_.c_str());
  }
}

// What the session holds, for soak runs (scripts/soak): memory that grows with the session's
// length rather than with what it shows is a leak.
void Viewer::reportMemory(const std::string& label) const {
  long size_pages = 0, resident_pages = 0;  // /proc/self/statm: total size, then resident, in pages
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld %ld", &size_pages, &resident_pages) != 2) resident_pages = 0;
    std::fclose(statm);
  }
  const double mib = 1.0 / (1 << 20);
  const double resident_mib = static_cast<double>(resident_pages) * static_cast<double>(::sysconf(_SC_PAGESIZE)) * mib;
  const lod::NodeCacheStats cache = cloud_ ? cloud_->cache->stats() : lod::NodeCacheStats{};
  const render::GpuNodeCacheStats gpu_nodes = cloud_ ? cloud_->renderer->gpuNodeStats() : render::GpuNodeCacheStats{};
  std::printf(
      "plumb view: memory %s: resident %.1f MiB, node cache %.1f MiB in %llu nodes, GPU %.1f MiB in use "
      "(%.1f reserved; nodes %.1f MiB), undo history %zu edits, scene %zu segments %zu polygons\n",
      label.c_str(), resident_mib, static_cast<double>(cache.bytes) * mib, static_cast<unsigned long long>(cache.nodes),
      static_cast<double>(allocator_.bytesInUse()) * mib, static_cast<double>(allocator_.bytesReserved()) * mib,
      static_cast<double>(gpu_nodes.bytes) * mib, scene_.history().undoCount(), scene_.registry().count<Segment>(),
      scene_.registry().count<Polygon>());
  std::fflush(stdout);
}

// glTF, OBJ, DXF and the CSVs beside the project: "<project without .plumbproj>.glb", ...
void Viewer::exportProject() {
  std::filesystem::path stem = project_.path();
  if (stem.extension() == ".plumbproj") stem.replace_extension();
  const cad::ExportTargets targets{.gltf = stem.string() + ".glb",
                                   .obj = stem.string() + ".obj",
                                   .dxf = stem.string() + ".dxf",
                                   .csv = stem.string() + "-corners.csv",
                                   .measurements = stem.string() + "-measurements.csv"};
  // Never over the cloud itself (a scan may be an OBJ or a CSV) or the project.
  const auto same = [](const std::string& a, const std::string& b) {
    std::error_code error;
    return !b.empty() && std::filesystem::weakly_canonical(a, error) == std::filesystem::weakly_canonical(b, error);
  };
  for (const std::string& target : {targets.gltf, targets.obj, targets.dxf, targets.csv, targets.measurements}) {
    if (same(target, options_.cloud) || same(target, project_.path())) {
      project_message_ = "not exported: " + target + " is the cloud or the project itself";
      std::printf("plumb view: %s\n", project_message_.c_str());
      return;
    }
  }
  try {
    const std::vector<std::string> written = cad::exportAll(currentProject(), targets);
    project_message_ = "exported " + std::to_string(written.size()) + " files to " + stem.string() + ".*";
  } catch (const std::exception& error) {
    project_message_ = error.what();
  }
  std::printf("plumb view: %s\n", project_message_.c_str());
}

// --- loading -----------------------------------------------------------------------------------

void Viewer::startLoading() {
  const std::shared_ptr<LoadProgress> progress = load_progress_;
  const auto report = [progress](std::string_view phase, double fraction) {
    const std::scoped_lock lock(progress->mutex);
    progress->phase = std::string(phase);
    progress->fraction = std::clamp(fraction, 0.0, 1.0);
  };
  const std::string cloud = options_.cloud;
  // An octree opens at once; a point file or the demo is made on a background job while the
  // window shows the progress.
  if (!cloud.empty() && lod::Octree::looksLikeOctree(cloud)) {
    openCloud(lod::Octree::open(cloud), "", options_.camera);
    progress->finished = true;
    return;
  }
  jobs_.submit(jobs::Priority::background, "load cloud", [this, progress, report, cloud](const jobs::CancelToken&) {
    try {
      std::string path = cloud, temporary;
      // The home view: the one given, else the demo's. (Assigned once: GCC 12 warned that an
      // optional Camera assigned on one branch "may be used uninitialized" when copied.)
      std::optional<view::Camera> demo_home;
      if (cloud.empty()) {
        const DemoScan demo = ensureDemoScan(report);
        path = demo.octree.string();
        demo_home = demo.home;
      } else {
        const std::string name = std::filesystem::path(cloud).filename().string();
        const auto build = [&](const std::string& output, std::uint64_t stride, const std::string& what) {
          {
            const std::scoped_lock lock(progress->mutex);
            progress->temporaries.push_back(output);
          }
          lod::BuildOptions options;
          options.sources = lod::fileSources({cloud});
          if (stride > 1) {
            for (lod::BuildSource& source : options.sources) {
              source.open = [open = source.open, stride] {
                return std::make_unique<io::SampledReader>(open(), stride);
              };
            }
          }
          options.output = output;
          options.progress = [&](std::string_view phase, std::uint64_t done, std::uint64_t total) {
            report(what + name + ": " + std::string(phase),
                   total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 0.0);
          };
          lod::buildOctree(options);
        };
        const std::string stem =
            (std::filesystem::temp_directory_path() / ("plumb-view-" + std::to_string(::getpid()))).string();
        // A big file shows a preview first, every k-th point, while the whole file is imported:
        // the view can be moved and grown on meanwhile, and the whole cloud takes its place.
        const std::uint64_t declared = io::openPointCloud(cloud)->info().declared_points.value_or(0);
        if (declared > 2 * kPreviewPoints) {
          const std::string preview = stem + "-preview.plumb";
          build(preview, declared / kPreviewPoints, "preview of ");
          std::shared_ptr<const lod::Octree> octree = lod::Octree::open(preview);
          jobs_.post([this, octree, preview, home = options_.camera] { openCloud(octree, preview, home, true); });
        }
        temporary = stem + ".plumb";
        build(temporary, 1, "importing ");
        path = temporary;
      }
      std::shared_ptr<const lod::Octree> octree = lod::Octree::open(path);
      const std::optional<view::Camera> home = options_.camera ? options_.camera : demo_home;
      jobs_.post([this, octree, temporary, home, progress] {
        openCloud(octree, temporary, home);
        const std::scoped_lock lock(progress->mutex);
        progress->finished = true;
      });
    } catch (const std::exception& error) {
      const std::scoped_lock lock(progress->mutex);
      progress->error = error.what();
      progress->finished = true;  // nothing more will come: a preview shown stays
    }
  });
}

void Viewer::openCloud(std::shared_ptr<const lod::Octree> octree, std::string temporary,
                       std::optional<view::Camera> home, bool preview) {
  // The whole cloud after its preview: the view stays where the user took it; a grow on the
  // preview stops (its finished segments stay: they are planes of the same surfaces).
  std::optional<view::Camera> current;
  if (cloud_) {
    current = cloud_->navigator->camera();
    cloud_->grow->cancel();
    scene_.dropLive();
    cloud_.reset();
  }
  auto cloud = std::make_unique<LoadedCloud>();
  cloud->octree = std::move(octree);
  cloud->temporary = std::move(temporary);
  cloud->cache = std::make_unique<lod::NodeCache>(cloud->octree, kNodeCacheBytes);
  // Node loads run at streaming priority: behind a grow the user waits for, ahead of imports.
  cloud->cache->setBackgroundRunner([this](std::function<void()> work) {
    jobs_.submit(jobs::Priority::streaming, "load node",
                 [work = std::move(work)](const jobs::CancelToken&) { work(); });
  });
  render::RendererOptions renderer_options;
  renderer_options.gpu_timing = options_.profile;
  // The surfels of streamed nodes too: the frame uploads a node once they are estimated.
  renderer_options.background = [this](std::function<void()> work) {
    jobs_.submit(jobs::Priority::streaming, "estimate surfels",
                 [work = std::move(work)](const jobs::CancelToken&) { work(); });
  };
  cloud->renderer = std::make_unique<render::PointRenderer>(device_, allocator_, *cloud->cache, renderer_options);
  try {
    cloud->framing = lod::framingBox(*cloud->octree);
  } catch (const Error& error) {
    // An older octree or a COPC file samples its shallow nodes for it: one that cannot be read
    // shows as the view loads it; frame the bounds meanwhile.
    cloud->framing = cloud->octree->header().bounds;
    std::fprintf(stderr, "plumb view: framing on the bounds: %s\n", error.what());
  }
  const lod::Box3& framing = cloud->framing;
  const VkExtent2D size = window_.framebufferSize();
  const int width =
      std::max(1, static_cast<int>(std::lround(std::max(1u, size.width) * static_cast<double>(render_scale_))));
  const int height =
      std::max(1, static_cast<int>(std::lround(std::max(1u, size.height) * static_cast<double>(render_scale_))));
  cloud->navigator =
      std::make_unique<Navigator>(Eigen::Vector3d(framing.min[0], framing.min[1], framing.min[2]),
                                  Eigen::Vector3d(framing.max[0], framing.max[1], framing.max[2]), width, height);
  cloud->navigator->setViewport(width, height, static_cast<int>(std::max(1u, size.width)));
  if (home) cloud->navigator->setHome(*home);
  if (current) cloud->navigator->setCamera(*current);
  cloud->grow = std::make_unique<GrowSession>(jobs_, *cloud->cache, [this](const GrowUpdate& update) {
    scene_.applyGrow(update);
    grow_panel_.last_update = update;
  });
  cloud->renderer->setPresentHook([this](VkCommandBuffer commands, const gpu::SwapchainImage& image) {
    imgui_.record(commands, image);
    if (pending_screenshot_) screenshots_.record(commands, image);
  });
  std::printf("plumb view: %s %llu points%s\n", current ? "now the whole cloud:" : "opened",
              static_cast<unsigned long long>(cloud->octree->header().point_count),
              preview ? ", a preview while the whole file is imported" : "");
  cloud_ = std::move(cloud);
  window_.setTitle("Plumb - " + (options_.cloud.empty() ? std::string("demo office scan") : options_.cloud));
}

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
    const bool busy = script_ || !cloud_ || (cloud_->grow && cloud_->grow->busy()) || !streamingIdle() ||
                      (cloud_->navigator && cloud_->navigator->flying()) || frames_ < 3;
    std::vector<InputEvent> events = window_.takeEvents(!busy, 0.5);

    std::optional<std::string> screenshot;
    if (script_) {
      const bool grower_idle = cloud_ && !(cloud_->grow && cloud_->grow->busy());
      ScriptFrame frame = script_->next(grower_idle, cloud_ && streamingIdle());
      if (frame.failure) {
        std::fprintf(stderr, "plumb view: %s: %s\n", options_.script.c_str(), frame.failure->c_str());
        exit_status_ = 1;
        break;
      }
      if (frame.finished) break;
      events.insert(events.end(), frame.events.begin(), frame.events.end());
      if (frame.tool) setTool(*frame.tool);
      if (frame.measure) {
        setTool(Tool::kMeasure);
        measure_.setKind(*frame.measure);
      }
      if (frame.grow_detail) grow_panel_.detail = *frame.grow_detail;
      if (frame.colour) settings_.colour = static_cast<render::ColourMode>(*frame.colour);
      if (frame.resize) window_.resize(frame.resize->first, frame.resize->second);
      if (frame.look && cloud_) {
        view::Camera camera = cloud_->navigator->camera();
        camera.position = frame.look->first;
        camera.target = frame.look->second;
        camera.up = Eigen::Vector3d::UnitZ();  // level, whatever the view before
        cloud_->navigator->setCamera(camera);
      }
      // Steps at world points: their window pixels in the view now.
      const auto windowPixel = [&](const Eigen::Vector3d& world) -> std::optional<Eigen::Vector2d> {
        const std::optional<Eigen::Vector2d> pixel = view::pixelOf(cloud_->navigator->camera(), world);
        if (!pixel) {
          std::fprintf(stderr, "plumb view: %s: the world point of a step is behind the camera\n",
                       options_.script.c_str());
          exit_status_ = 1;
          quit_ = true;
          return std::nullopt;
        }
        return Eigen::Vector2d(*pixel / renderScale());
      };
      const auto mouse = [](InputEvent::Kind kind, const Eigen::Vector2d& at, bool pressed = false) {
        return InputEvent{.kind = kind, .x = at.x(), .y = at.y(), .button = GLFW_MOUSE_BUTTON_LEFT, .pressed = pressed};
      };
      const std::array<std::pair<std::optional<Eigen::Vector3d>, bool>, 2> world_steps{
          {{frame.click_world, true}, {frame.move_world, false}}};
      for (const auto& [world, press] : world_steps) {
        if (!world || !cloud_) continue;
        const std::optional<Eigen::Vector2d> at = windowPixel(*world);
        if (!at) break;
        events.push_back(mouse(InputEvent::Kind::kMouseMove, *at));
        if (press) {
          events.push_back(mouse(InputEvent::Kind::kMouseButton, *at, true));
          events.push_back(mouse(InputEvent::Kind::kMouseButton, *at, false));
        }
      }
      if (frame.drag_world && cloud_ && !quit_) {
        const std::optional<Eigen::Vector2d> from = windowPixel(frame.drag_world->from);
        const std::optional<Eigen::Vector2d> to = from ? windowPixel(frame.drag_world->to) : std::nullopt;
        if (from && to) {
          events.push_back(mouse(InputEvent::Kind::kMouseMove, *from));
          events.push_back(mouse(InputEvent::Kind::kMouseButton, *from, true));
          for (int i = 1; i <= frame.drag_world->steps; ++i) {
            const double t = static_cast<double>(i) / frame.drag_world->steps;
            events.push_back(mouse(InputEvent::Kind::kMouseMove, *from + t * (*to - *from)));
          }
          events.push_back(mouse(InputEvent::Kind::kMouseButton, *to, false));
        }
      }
      if (quit_) break;
      if (frame.memory) reportMemory(*frame.memory);
      screenshot = frame.screenshot;
    }

    for (const InputEvent& event : events) imgui_.feed(event);
    jobs_.drainContinuations();  // grow snapshots into the scene, a finished import

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
    render(screenshot.has_value(), screenshot.value_or(""));
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

void Viewer::handleEvents(const std::vector<InputEvent>& events) {
  for (const InputEvent& event : events) {
    if (event.kind == InputEvent::Kind::kMouseMove || event.kind == InputEvent::Kind::kMouseButton) {
      mouse_x_ = event.x;
      mouse_y_ = event.y;
    }
    if (event.kind == InputEvent::Kind::kClose) {
      quit_ = true;
      continue;
    }
    const bool mouse = event.kind == InputEvent::Kind::kMouseMove || event.kind == InputEvent::Kind::kMouseButton ||
                       event.kind == InputEvent::Kind::kWheel;
    const bool keyboard = event.kind == InputEvent::Kind::kKey || event.kind == InputEvent::Kind::kCharacter;
    // The palette has the mouse unless a drag on the view is under way (a release must end it).
    const bool dragging = (cloud_ && cloud_->navigator->dragging()) || box_drag_.has_value();
    if (mouse && imgui_.wantsMouse() && !dragging) continue;
    if (keyboard && imgui_.wantsKeyboard()) continue;
    handleViewEvent(event);
  }
}

// Keys of the drawing tools: Shift locks the direction; while a tool has begun, digits, '.',
// '-', Backspace and Enter type a distance (and are not view presets). True when taken.
bool Viewer::drawingKey(const InputEvent& event) {
  if (event.kind == InputEvent::Kind::kKey && (event.key == GLFW_KEY_LEFT_SHIFT || event.key == GLFW_KEY_RIGHT_SHIFT)) {
    drawing_.lockDirection(event.pressed);
    return false;  // the navigator's fast flight sees Shift too
  }
  const DrawingState& d = scene_.tool().drawing;
  const bool begun = !d.vertices.empty() || d.base || d.polygon != ecs::kNullEntity;
  if (!isDrawingTool(scene_.tool().active) || !begun || !cloud_) return false;
  if (event.kind == InputEvent::Kind::kCharacter) {
    if (event.codepoint < 128) drawing_.type(static_cast<char>(event.codepoint));
    return true;
  }
  if (event.kind != InputEvent::Kind::kKey) return false;
  const bool typing = (event.key >= GLFW_KEY_0 && event.key <= GLFW_KEY_9) || event.key == GLFW_KEY_PERIOD ||
                      event.key == GLFW_KEY_MINUS || (event.key >= GLFW_KEY_KP_0 && event.key <= GLFW_KEY_KP_9) ||
                      event.key == GLFW_KEY_KP_DECIMAL || event.key == GLFW_KEY_KP_SUBTRACT ||
                      event.key == GLFW_KEY_SLASH || event.key == GLFW_KEY_KP_DIVIDE || event.key == GLFW_KEY_X ||
                      event.key == GLFW_KEY_KP_MULTIPLY;
  if (typing) return true;  // the character event that follows carries it
  if (!event.pressed) return false;
  if (event.key == GLFW_KEY_BACKSPACE) {
    drawing_.backspace();
    return true;
  }
  if (event.key == GLFW_KEY_ENTER || event.key == GLFW_KEY_KP_ENTER) {
    drawing_.enter(pointerAt(hovered_px_.x(), hovered_px_.y(), false), cloud_->navigator->camera());
    return true;
  }
  return false;
}

void Viewer::handleViewEvent(const InputEvent& event) {
  if (event.kind == InputEvent::Kind::kKey &&
      (event.key == GLFW_KEY_LEFT_CONTROL || event.key == GLFW_KEY_RIGHT_CONTROL)) {
    control_held_ = event.pressed;
  }
  if (event.kind == InputEvent::Kind::kKey && (event.key == GLFW_KEY_LEFT_SHIFT || event.key == GLFW_KEY_RIGHT_SHIFT)) {
    shift_held_ = event.pressed;
  }
  if (drawingKey(event)) return;
  if (event.kind == InputEvent::Kind::kKey && event.pressed) {
    const bool control = (event.mods & GLFW_MOD_CONTROL) != 0 || control_held_;
    if (control && event.key == GLFW_KEY_Z) return undo();
    if (control && event.key == GLFW_KEY_Y) return redo();
    if (control && event.key == GLFW_KEY_S) return saveProject();
    if (control && event.key == GLFW_KEY_E) return exportProject();
    if (control && event.key == GLFW_KEY_G) {
      groupSelected();
      return;
    }
    if (event.key == GLFW_KEY_DELETE) return deleteSelected();
    if (event.key == GLFW_KEY_ESCAPE) {
      if (cloud_ && cloud_->grow) cloud_->grow->cancel();
      drawing_.escape();
      measure_.escape();
      return;
    }
    if (!control) {
      switch (event.key) {
        case GLFW_KEY_N:
          return setTool(Tool::kNavigate);
        case GLFW_KEY_G:
          return setTool(Tool::kGrow);
        case GLFW_KEY_M:
          return setTool(Tool::kMeasure);
        case GLFW_KEY_P:
          return setTool(Tool::kPolygon);
        case GLFW_KEY_V:
          return setTool(Tool::kMove);
        case GLFW_KEY_E:
          if (!(cloud_ && cloud_->navigator->flying())) return setTool(Tool::kExtrude);
          break;
        case GLFW_KEY_R:
          scene_.registry().patch<ToolState>(scene_.toolEntity(),
                                             [](ToolState& t) { t.drawing.rectangle = !t.drawing.rectangle; });
          return;
        case GLFW_KEY_C:
          scene_.registry().patch<ToolState>(scene_.toolEntity(),
                                             [](ToolState& t) { t.drawing.copy = !t.drawing.copy; });
          return;
        case GLFW_KEY_K:
          return cornerOfSelected();
        case GLFW_KEY_X:
          return clipAtSelectedPlane();
        case GLFW_KEY_PAGE_UP:
        case GLFW_KEY_PAGE_DOWN:
          // The slice steps through the building by its thickness; without one, the slab along
          // its normal.
          if (clip_.slice) {
            clip_.slice_bottom_z += (event.key == GLFW_KEY_PAGE_UP ? 1.0 : -1.0) * clip_.slice_thickness;
            return;
          }
          if (clip_.slab) {
            clip_.slab->point +=
                (event.key == GLFW_KEY_PAGE_UP ? 1.0 : -1.0) * clip_.slab->thickness * clip_.slab->normal;
            return;
          }
          break;
        default:
          break;
      }
    }
  }
  if (!cloud_) return;
  if (clipBoxEvent(event)) return;
  // The navigator works in window pixels (a drag turns the view as far whatever the render scale,
  // which changes while the view moves); picks and the tools in render pixels (the window's, times
  // the render scale).
  const double scale = renderScale();
  const bool clicked =
      cloud_->navigator->handle(event, [this, scale](double x, double y) { return pickAt(x * scale, y * scale); });
  if (clicked) click(event.x * scale, event.y * scale);
}

// The scene's overlay, with the clip box's edges and handles when there is one. Made anew only
// when the scene's overlay, the box or the lit handle changed.
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
std::uint64_t Viewer::documentState() const {
  return documentVersion(scene_.registry()) * 0x9E3779B97F4A7C15ull + sectionDigest(clip_);
}

// The clip box's handles: a left press on one starts dragging it (Shift: the centre up and down),
// moves drag it, the release ends it; the navigator and the tools see none of these. Without a
// drag, moves only light the handle under the cursor. True when taken.
bool Viewer::clipBoxEvent(const InputEvent& event) {
  if (!clip_.box) {
    box_drag_.reset();
    hovered_box_handle_.reset();
    return false;
  }
  const double scale = renderScale();
  const view::Camera& camera = cloud_->navigator->camera();
  const view::Ray ray = view::rayThroughPixel(camera, event.x * scale, event.y * scale);
  if (event.kind == InputEvent::Kind::kMouseMove) {
    if (box_drag_) {
      clip_.box = box_drag_->boxFor(ray);
      return true;
    }
    hovered_box_handle_ = boxHandleAt(*clip_.box, camera, event.x * scale, event.y * scale);
    return false;
  }
  if (event.kind != InputEvent::Kind::kMouseButton || event.button != GLFW_MOUSE_BUTTON_LEFT) return false;
  if (!event.pressed) {
    const bool dragging = box_drag_.has_value();
    box_drag_.reset();
    return dragging;
  }
  const std::optional<BoxHandle> handle = boxHandleAt(*clip_.box, camera, event.x * scale, event.y * scale);
  if (!handle) return false;
  box_drag_.emplace(*clip_.box, *handle, ray, (event.mods & GLFW_MOD_SHIFT) != 0 || shift_held_);
  return true;
}

std::optional<Eigen::Vector3d> Viewer::pickAt(double x_px, double y_px) {
  if (!cloud_ || last_stats_.frame == 0) return std::nullopt;
  const std::optional<render::PickedPoint> picked =
      cloud_->renderer->pick(static_cast<int>(x_px), static_cast<int>(y_px), 4);
  if (!picked) return std::nullopt;
  return Eigen::Vector3d(picked->position[0], picked->position[1], picked->position[2]);
}

// What the pointer at (x, y) (render pixels) snaps to, with its ray and movement; a click also
// asks the frame for the cloud's point under it.
Pointer Viewer::pointerAt(double x_px, double y_px, bool pick_point) {
  const view::Camera& camera = cloud_->navigator->camera();
  Pointer pointer;
  pointer.snap = snapCursor(scene_.registry(), camera, x_px, y_px,
                            pick_point ? PointPicker([this](double x, double y) { return pickAt(x, y); }) : nullptr);
  pointer.ray = view::rayThroughPixel(camera, x_px, y_px);
  pointer.pixel = Eigen::Vector2d(x_px, y_px);
  pointer.motion_px = pointer.pixel - hovered_px_;
  return pointer;
}

// Navigate: a click selects the polygon or segment under the cursor (Ctrl adds or removes).
void Viewer::selectAt(double x_px, double y_px) {
  const view::Camera& camera = cloud_->navigator->camera();
  ecs::Entity entity = polygonAt(scene_.registry(), camera, x_px, y_px);
  if (entity == ecs::kNullEntity) {
    SnapOptions walls_too;
    walls_too.edge_on_planes = true;
    const std::optional<Snap> snap = snapCursor(scene_.registry(), camera, x_px, y_px, {}, walls_too);
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

void Viewer::click(double x_px, double y_px) {
  const Tool tool = scene_.tool().active;
  if (tool == Tool::kNavigate) return selectAt(x_px, y_px);
  if (isDrawingTool(tool)) {
    const Pointer pointer = pointerAt(x_px, y_px, true);
    drawing_.click(pointer, cloud_->navigator->camera());
    hovered_px_ = pointer.pixel;
    return;
  }
  if (tool == Tool::kGrow) {
    const std::optional<Eigen::Vector3d> picked = pickAt(x_px, y_px);
    if (picked) startGrow(*picked);  // nothing on the background
    return;
  }
  measure_.click(cloud_->navigator->camera(), x_px, y_px, [this](double x, double y) { return pickAt(x, y); });
}

// In the Measure and drawing tools, what the cursor would snap to (features only: no readback
// of the frame), and the drawing tools' preview and direction.
void Viewer::updateHover() {
  std::optional<Snap> hover;
  const Tool tool = scene_.tool().active;
  if (cloud_ && (tool == Tool::kMeasure || isDrawingTool(tool)) && !imgui_.wantsMouse()) {
    const Pointer pointer = pointerAt(mouse_x_ * renderScale(), mouse_y_ * renderScale(), false);
    hover = tool == Tool::kMeasure ? snapCursor(scene_.registry(), cloud_->navigator->camera(), pointer.pixel.x(),
                                                pointer.pixel.y(), nullptr, MeasureTool::snapOptionsFor(scene_.tool()))
                                   : pointer.snap;
    if (isDrawingTool(tool)) {
      drawing_.hover(pointer, cloud_->navigator->camera());
      hovered_px_ = pointer.pixel;
    }
  }
  const std::optional<Snap>& now = scene_.tool().hover;
  const bool same = hover.has_value() == now.has_value() &&
                    (!hover || (hover->kind == now->kind && (hover->position - now->position).norm() < 1e-9));
  if (!same) scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& state) { state.hover = hover; });
}

// The grow parameters of a click at `picked` in the current view, with the panel's t_p and
// detail, the view's detail following `data` (the cloud at the click); nothing when the point
// lies behind the eye.
std::optional<reco::GrowParameters> Viewer::clickParameters(const Eigen::Vector3d& picked,
                                                            const std::optional<reco::DataAtClick>& data) const {
  const view::Camera& camera = cloud_->navigator->camera();
  // The screen the user sees: the window, not the render's scaled viewport.
  const std::optional<reco::ViewAtClick> view =
      viewAtClick(camera, picked, camera.viewport_width_px / renderScale(), camera.viewport_height_px / renderScale());
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

void Viewer::startGrow(const Eigen::Vector3d& picked) {
  // The data's spacing where the user clicked, for the view's detail (a few nodes, most of them
  // loaded for the picture already).
  if (grow_panel_.detail == 0) grow_panel_.last_data = reco::dataAtClick(*cloud_->cache, picked);
  const std::optional<reco::GrowParameters> parameters = clickParameters(picked, grow_panel_.last_data);
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
      cloud_->renderer->render(cloud_->navigator->camera(), frame_settings, render::NodeLoading::kStream, &*image);
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
