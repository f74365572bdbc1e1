#include "ui/viewer/project_session.h"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "cad/project_file.h"
#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "ui/viewer/demo_scan.h"

namespace plumb::viewer {
namespace {

bool processCanWriteTo(const std::string& directory) { return ::access(directory.c_str(), W_OK) == 0; }

// FNV-1a (Fowler, Noll and Vo), 64 bits: the same digits for the same path on every machine and
// build, which std::hash does not promise.
std::uint64_t fnv1a64(const std::string& text) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return hash;
}

}  // namespace

std::string defaultProjectPath(const std::string& cloud, bool (*directory_writable)(const std::string&)) {
  namespace fs = std::filesystem;
  const fs::path beside = cloud + ".plumbproj";
  std::error_code error;
  if (fs::exists(beside, error)) return beside.string();
  // Symbolic links and "." or ".." resolved, so that every way of naming the cloud finds one project.
  fs::path resolved = fs::weakly_canonical(fs::absolute(cloud), error);
  if (error) resolved = fs::absolute(cloud).lexically_normal();
  if ((directory_writable ? directory_writable : processCanWriteTo)(resolved.parent_path().string())) {
    return beside.string();
  }
  char digits[17];
  std::snprintf(digits, sizeof digits, "%016llx",
                static_cast<unsigned long long>(fnv1a64(resolved.string())));
  const fs::path projects = userCacheDirectory() / "projects";
  fs::create_directories(projects, error);
  if (error) throw Error(projects.string() + ": cannot create the projects directory: " + error.message());
  return (projects / (resolved.filename().string() + "-" + digits + ".plumbproj")).string();
}

ProjectSession ProjectSession::open(const std::string& path, const std::string& cloud) {
  ProjectSession session;
  if (!path.empty()) {
    session.path_ = path;
  } else if (cloud.empty()) {
    session.path_ = (userCacheDirectory() / "demo.plumbproj").string();
  } else {
    session.path_ = defaultProjectPath(cloud);
    session.in_cache_ = session.path_ != cloud + ".plumbproj";
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
