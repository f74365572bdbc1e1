// Where a cloud's project goes when none is named: beside the cloud where its folder takes new
// files, else the cache directory, under a name that keeps clouds apart and finds the same
// project again.

#include "ui/viewer/project_session.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "tests/support/temp_directory.h"

namespace plumb::viewer {
namespace {

bool writable(const std::string&) { return true; }
bool readOnly(const std::string&) { return false; }

// XDG_CACHE_HOME pointed at a test's directory for the test's length, so that nothing lands in the
// user's cache.
class CacheHome {
 public:
  explicit CacheHome(const std::filesystem::path& directory) {
    if (const char* old = std::getenv("XDG_CACHE_HOME")) old_ = old;
    ::setenv("XDG_CACHE_HOME", directory.c_str(), 1);
  }
  ~CacheHome() {
    if (old_) {
      ::setenv("XDG_CACHE_HOME", old_->c_str(), 1);
    } else {
      ::unsetenv("XDG_CACHE_HOME");
    }
  }
  CacheHome(const CacheHome&) = delete;
  CacheHome& operator=(const CacheHome&) = delete;

 private:
  std::optional<std::string> old_;
};

TEST(ProjectSession, AProjectGoesBesideACloudWhoseFolderTakesNewFiles) {
  const test::TempDirectory dir;
  const CacheHome cache(dir.path() / "cache");
  const std::string cloud = dir.write("scan.las", "");
  EXPECT_EQ(defaultProjectPath(cloud, writable), cloud + ".plumbproj");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "cache"));
}

TEST(ProjectSession, AReadOnlyFolderSendsTheProjectToTheCacheUnderANameOfTheCloudsOwn) {
  const test::TempDirectory dir;
  const CacheHome cache(dir.path() / "cache");
  std::filesystem::create_directories(dir.path() / "site a");
  std::filesystem::create_directories(dir.path() / "site b");
  const std::string a = dir.write("site a/scan.las", "");
  const std::string b = dir.write("site b/scan.las", "");

  const std::filesystem::path project_a = defaultProjectPath(a, readOnly);
  EXPECT_EQ(project_a.parent_path(), dir.path() / "cache" / "plumb" / "projects");
  EXPECT_TRUE(std::filesystem::is_directory(project_a.parent_path()));
  const std::string name = project_a.filename().string();
  ASSERT_EQ(name.size(), std::string("scan.las-").size() + 16 + std::string(".plumbproj").size()) << name;
  EXPECT_EQ(name.substr(0, 9), "scan.las-");
  EXPECT_EQ(name.substr(25), ".plumbproj");
  EXPECT_EQ(name.substr(9, 16).find_first_not_of("0123456789abcdef"), std::string::npos) << name;

  // Another cloud of the same name elsewhere keeps its own project.
  EXPECT_NE(defaultProjectPath(b, readOnly), project_a.string());
  // The same cloud, however it is named on the command line, finds the same project again.
  EXPECT_EQ(defaultProjectPath(a, readOnly), project_a.string());
  const std::filesystem::path relative = std::filesystem::relative(a);
  EXPECT_EQ(defaultProjectPath((relative.parent_path() / "." / relative.filename()).string(), readOnly),
            project_a.string());
}

TEST(ProjectSession, AProjectAlreadyBesideTheCloudIsOpenedThereEvenInAReadOnlyFolder) {
  const test::TempDirectory dir;
  const CacheHome cache(dir.path() / "cache");
  const std::string cloud = dir.write("scan.las", "");
  dir.write("scan.las.plumbproj", "{}");
  EXPECT_EQ(defaultProjectPath(cloud, readOnly), cloud + ".plumbproj");
}

}  // namespace
}  // namespace plumb::viewer
