#include "ui/viewer/project_session.h"

#include <filesystem>

#include "cad/project_file.h"
#include "engine/core/atomic_file.h"
#include "ui/viewer/demo_scan.h"

namespace plumb::viewer {

ProjectSession ProjectSession::open(const std::string& path, const std::string& cloud) {
  ProjectSession session;
  if (!path.empty()) {
    session.path_ = path;
  } else if (cloud.empty()) {
    session.path_ = (userCacheDirectory() / "demo.plumbproj").string();
  } else {
    session.path_ = cloud + ".plumbproj";
  }
  namespace fs = std::filesystem;
  std::error_code error;
  const bool project_exists = fs::exists(session.path_, error);
  const bool autosave_exists = fs::exists(session.autosavePath(), error);
  // The autosave holds later work than the project when it is newer (or the project was never saved).
  const bool autosave_newer =
      autosave_exists && (!project_exists || fs::last_write_time(session.autosavePath(), error) >
                                                 fs::last_write_time(session.path_, error));
  if (autosave_newer) {
    session.opened_ = cad::readProjectFile(session.autosavePath());
    session.recovered_ = true;
    if (project_exists) cad::readProjectFile(session.path_);  // a corrupt project is reported, not hidden
  } else if (project_exists) {
    session.opened_ = cad::readProjectFile(session.path_);
  }
  return session;
}

void ProjectSession::save(const cad::Project& project, std::uint64_t version) {
  cad::writeProjectFile(project, path_);
  std::error_code ignored;
  std::filesystem::remove(autosavePath(), ignored);
  removeAbandonedTemporaries(autosavePath());  // of autosaves a killed session did not finish
  recovered_ = false;
  markSaved(version);
}

bool ProjectSession::autosaveDue(std::uint64_t version, Clock::time_point now) const {
  return version != saved_version_ && version != autosaved_version_ && now - last_autosave_ >= autosave_interval_;
}

void ProjectSession::autosave(const cad::Project& project, std::uint64_t version, Clock::time_point now) {
  cad::writeProjectFile(project, autosavePath());
  autosaved_version_ = version;
  last_autosave_ = now;
}

}  // namespace plumb::viewer
