#pragma once
// The project a viewer session edits (.plumbproj, cad/project_file.h): where it is saved, whether
// the scene has changes it lacks, and the autosave beside it ("<project>.autosave"), so that
// nothing is lost when the viewer stops without a save.
//
//   open      the project file, or its autosave when that is newer (the work of a session that
//             stopped unsaved), or nothing (a new project, saved there on the first save)
//   save      the project file, atomically; the autosave goes
//   autosave  at most every autosave interval (30 s unless set) while there are unsaved changes,
//             and on exit: a session stopped by anything, SIGKILL included, loses at most the
//             edits of the last interval (both files are written atomically, core/atomic_file.h)
//
// The project file itself is written only by save: a corrupt or newer file is never overwritten
// by an autosave, and opening one fails before any window opens.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "cad/project.h"

namespace plumb::viewer {

// Where a cloud's project goes when none is named: "<cloud>.plumbproj" beside the cloud where one
// is there already or the cloud's folder takes new files; otherwise (a survey's read-only data
// folder, a mounted archive) "projects/<cloud's name>-<16 hex digits>.plumbproj" in the cache
// directory, the digits a hash of the cloud's absolute path, so that two clouds of one name in
// different folders keep their own projects, and every session of the same cloud finds its own.
// `directory_writable` decides what "takes new files" means (the process's write access unless a
// test says otherwise).
std::string defaultProjectPath(const std::string& cloud,
                               bool (*directory_writable)(const std::string& directory) = nullptr);

class ProjectSession {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kDefaultAutosaveInterval{30'000};

  // The session of `path`; an empty path gives the default (defaultProjectPath), or the cache
  // directory's "demo.plumbproj" for the demo (empty `cloud`). Reads the
  // project (or its newer autosave) when one exists. Throws plumb::Error naming the file and
  // the place for one that cannot be read, is corrupt or is newer than this build reads.
  static ProjectSession open(const std::string& path, const std::string& cloud);

  const std::string& path() const { return path_; }
  // True when the default project of a cloud went to the cache directory (defaultProjectPath).
  bool inCache() const { return in_cache_; }
  std::string autosavePath() const { return path_ + ".autosave"; }
  // What was read, to load into the scene (once: take it).
  std::optional<cad::Project> takeOpened() { return std::exchange(opened_, std::nullopt); }
  // True when what was opened is the autosave (unsaved work of an earlier session).
  bool recovered() const { return recovered_; }

  // The scene's document version (project_bridge.h) that matches the file now.
  void markSaved(std::uint64_t version) { saved_version_ = autosaved_version_ = version; }
  bool unsaved(std::uint64_t version) const { return version != saved_version_; }

  // Writes the project file and removes the autosave. Throws plumb::Error (the file as it was).
  void save(const cad::Project& project, std::uint64_t version);
  void setAutosaveInterval(std::chrono::milliseconds interval) { autosave_interval_ = interval; }
  // True when changes wait that the autosave lacks, and the last autosave is an interval old.
  bool autosaveDue(std::uint64_t version, Clock::time_point now) const;
  // Writes the autosave. Throws plumb::Error.
  void autosave(const cad::Project& project, std::uint64_t version, Clock::time_point now);

 private:
  std::string path_;
  std::optional<cad::Project> opened_;
  bool recovered_ = false;
  bool in_cache_ = false;
  std::uint64_t saved_version_ = 0;
  std::uint64_t autosaved_version_ = 0;
  Clock::time_point last_autosave_ = Clock::now();
  std::chrono::milliseconds autosave_interval_ = kDefaultAutosaveInterval;
};

}  // namespace plumb::viewer
