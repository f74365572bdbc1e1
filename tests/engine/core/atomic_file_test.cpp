#include "engine/core/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "tests/support/temp_directory.h"

namespace plumb {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  std::size_t entries() const { return temp_.entryCount(); }

  test::TempDirectory temp_;
  fs::path directory_ = temp_.path();
};

TEST_F(AtomicFileTest, AppearsOnlyOnCommit) {
  const fs::path target = directory_ / "out.bin";
  {
    AtomicFile file(target.string());
    file.write("hello ", 6);
    file.write("world", 5);
    EXPECT_EQ(file.size(), 11u);
    EXPECT_FALSE(fs::exists(target));
    file.commit();
  }
  EXPECT_EQ(test::readFile(target.string()), "hello world");
  EXPECT_EQ(entries(), 1u);  // no temporary left beside it
}

TEST_F(AtomicFileTest, DestroyedBeforeCommitLeavesNothing) {
  const fs::path target = directory_ / "out.bin";
  {
    AtomicFile file(target.string());
    file.write("partial", 7);
    file.finish();
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(AtomicFileTest, ReplacesAnExistingFileOnlyOnCommit) {
  const fs::path target = directory_ / "out.bin";
  std::ofstream(target) << "old";
  {
    AtomicFile file(target.string());
    file.write("new", 3);
  }
  EXPECT_EQ(test::readFile(target.string()), "old");
  AtomicFile file(target.string());
  file.write("new", 3);
  file.commit();
  EXPECT_EQ(test::readFile(target.string()), "new");
}

TEST_F(AtomicFileTest, OverwritePatchesEarlierBytesAcrossTheBuffer) {
  const fs::path target = directory_ / "out.bin";
  AtomicFile file(target.string());
  file.write("0000", 4);
  const std::string big(3 << 20, 'x');  // larger than the write buffer
  file.write(big.data(), big.size());
  file.write("tail", 4);
  const char patch[] = "1234";
  file.overwrite(0, std::as_bytes(std::span(patch, 4)));
  file.commit();
  const std::string text = test::readFile(target.string());
  ASSERT_EQ(text.size(), 4 + big.size() + 4);
  EXPECT_EQ(text.substr(0, 4), "1234");
  EXPECT_EQ(text.substr(text.size() - 4), "tail");
}

TEST_F(AtomicFileTest, MissingFolderIsAClearError) {
  const fs::path target = directory_ / "no" / "such" / "folder" / "out.bin";
  try {
    AtomicFile file(target.string());
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(target.string()), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("cannot create"), std::string::npos) << error.what();
  }
}

TEST_F(AtomicFileTest, DirectoryAsTargetIsAClearError) {
  EXPECT_THROW(AtomicFile(directory_.string()), Error);
}

TEST_F(AtomicFileTest, TerminatedProcessLeavesNoTemporary) {
  const fs::path target = directory_ / "out.bin";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    AtomicFile file(target.string());
    file.write("interrupted", 11);
    std::raise(SIGTERM);
    _exit(0);  // not reached: SIGTERM ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_EQ(entries(), 0u);
}

// SIGKILL cannot be caught: the temporary stays until the next AtomicFile of that path, which
// removes it; a temporary of a process that still runs (this one's, another target's) stays.
TEST_F(AtomicFileTest, AKilledProcessTemporaryGoesWithTheNextWriteOfThatPath) {
  const fs::path target = directory_ / "out.bin";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    AtomicFile file(target.string());
    file.write("killed", 6);
    file.finish();
    std::raise(SIGKILL);
    _exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  ASSERT_EQ(entries(), 1u) << "the killed process's temporary";
  const fs::path running = directory_ / ("out.bin.partial-" + std::to_string(::getppid()) + "-0");
  std::ofstream(running) << "a running process's";
  const fs::path other = directory_ / ("other.bin.partial-" + std::to_string(child) + "-0");
  std::ofstream(other) << "another target's";

  AtomicFile file(target.string());
  file.write("next", 4);
  file.commit();
  EXPECT_EQ(entries(), 3u) << "the output, the running process's and the other target's temporaries";
  EXPECT_TRUE(fs::exists(running));
  EXPECT_TRUE(fs::exists(other));
}

}  // namespace
}  // namespace plumb
