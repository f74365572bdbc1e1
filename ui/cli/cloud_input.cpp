#include "ui/cli/cloud_input.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string_view>

#include "engine/lod/octree.h"
#include "engine/lod/octree_builder.h"
#include "ui/cli/arguments.h"
#include "ui/cli/progress_line.h"

namespace plumb::cli {

CloudInput::CloudInput(const std::string& path, const std::string& command) {
  std::string octree_path = path;
  if (!lod::Octree::looksLikeOctree(path)) {
    temporary_path_ =
        (std::filesystem::temp_directory_path() / ("plumb-" + command + "-" + std::to_string(::getpid()) + ".plumb"))
            .string();
    lod::BuildOptions build;
    build.sources = lod::fileSources({path});
    build.output = temporary_path_;
    ProgressLine progress(command + ": importing");
    build.progress = [&](std::string_view phase, std::uint64_t done, std::uint64_t total) {
      progress.update(phase, done, total);
    };
    const lod::BuildReport report = lod::buildOctree(build);
    progress.finish();
    std::printf("imported %s points from %s\n", withThousands(report.points).c_str(), path.c_str());
    octree_path = temporary_path_;
  }
  octree_ = lod::Octree::open(octree_path);
}

CloudInput::~CloudInput() {
  octree_.reset();
  if (!temporary_path_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temporary_path_, ignored);
  }
}

}  // namespace plumb::cli
