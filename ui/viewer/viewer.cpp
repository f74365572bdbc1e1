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
#include "ui/xr/xr_runtime.h"
#include "ui/xr/xr_session.h"

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

constexpr std::size_t kNodeCacheBytes = std::size_t{1} << 30;
constexpr std::uint64_t kPreviewPoints = 500'000;  // an import's preview holds about this many

gpu::DeviceChoice deviceChoice(const ViewerOptions& options, VkSurfaceKHR surface, gpu::VulkanFactory* headset) {
  gpu::DeviceChoice choice =
      options.gpu.empty() ? gpu::deviceChoiceFromEnvironment() : gpu::DeviceChoice{.prefer = options.gpu};
  choice.present_to = surface;
  choice.factory = headset;
  return choice;
}

gpu::InstanceOptions instanceOptions(gpu::VulkanFactory* headset) {
  gpu::InstanceOptions options = gpu::instanceOptionsFromEnvironment();
  options.factory = headset;
  return options;
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
      xr_runtime_(options.xr ? connectHeadset() : nullptr),
      instance_(instanceOptions(xr_runtime_.get()), windows_.requiredInstanceExtensions()),
      window_(windows_, options.width, options.height, "Plumb"),
      surface_(window_.createSurface(instance_.handle())),
      device_(instance_, deviceChoice(options, surface_, xr_runtime_.get())),
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
  xr_resolution_scale_ = options.xr_resolution_scale > 0.0 ? options.xr_resolution_scale : (cpu ? 0.5 : 1.0);
  openProject();
  startLoading();
  if (xr_runtime_) startHeadsetSession();
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
  xr_session_.reset();  // before the device its swapchains live on
}

// --- the project --------------------------------------------------------------------------------

// The project's items into the scene; its cloud and first view unless the command line gave them.
void Viewer::openProject() {
  std::optional<cad::Project> project = project_.takeOpened();
  if (!project) {
    project_.markSaved(documentState());
    if (project_.inCache()) {
      project_message_ = "the cloud's folder takes no new files: the project goes to " + project_.path();
      std::printf("plumb view: %s\n", project_message_.c_str());
    }
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

std::uint64_t Viewer::documentState() const {
  return documentVersion(scene_.registry()) * 0x9E3779B97F4A7C15ull + sectionDigest(clip_);
}

// The clip box's handles: a left press on one starts dragging it (Shift: the centre up and down),
// moves drag it, the release ends it; the navigator and the tools see none of these. Without a
// drag, moves only light the handle under the cursor. True when taken.

}  // namespace plumb::viewer
