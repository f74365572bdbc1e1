#pragma once
// The CLOUD argument of the commands that read a cloud (grow, render): a built octree, or a
// point file imported into a temporary octree that is removed when the command ends.

#include <memory>
#include <string>

namespace plumb::lod {
class Octree;
}

namespace plumb::cli {

class CloudInput {
 public:
  // Opens `path`; a point file is imported first, with a progress line headed `command`.
  // Throws plumb::Error naming the file for what cannot be read.
  CloudInput(const std::string& path, const std::string& command);
  ~CloudInput();
  CloudInput(const CloudInput&) = delete;
  CloudInput& operator=(const CloudInput&) = delete;

  const std::shared_ptr<const lod::Octree>& octree() const { return octree_; }

 private:
  std::string temporary_path_;  // empty for an octree given as such
  std::shared_ptr<const lod::Octree> octree_;
};

}  // namespace plumb::cli
