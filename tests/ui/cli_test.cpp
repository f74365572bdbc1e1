// The plumb executable as a user meets it: help, argument errors, exit codes, outputs.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code;
  std::string out;
  std::string err;
};

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("plumb_cli_" + std::to_string(::getpid()) + "_" +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  // Runs plumb with `arguments` (shell words), no standard input.
  Outcome plumb(const std::string& arguments) const {
    const fs::path out = directory_ / "stdout.txt", err = directory_ / "stderr.txt";
    const std::string command =
        std::string(PLUMB_BINARY) + " " + arguments + " </dev/null >" + out.string() + " 2>" + err.string();
    const int status = std::system(command.c_str());
    Outcome run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readAll(out), readAll(err)};
    fs::remove(out);
    fs::remove(err);
    return run;
  }
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(directory_), fs::directory_iterator()));
  }
  std::string path(const std::string& name) const { return (directory_ / name).string(); }

  fs::path directory_;
};

TEST_F(Cli, HelpListsTheCommands) {
  const Outcome run = plumb("--help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("simulate"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("plumb <command> --help"), std::string::npos) << run.out;
}

TEST_F(Cli, CommandHelpListsItsOptions) {
  const Outcome run = plumb("simulate --help");
  EXPECT_EQ(run.exit_code, 0);
  for (const char* option : {"--scene", "--points", "--noise-mm", "--seed", "--offset", "--output", "--truth",
                             "--stations", "--rotate-deg", "--dropout", "--max-range"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
}

TEST_F(Cli, NoCommandIsAnErrorOnStderr) {
  const Outcome run = plumb("");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_NE(run.err.find("subcommand"), std::string::npos) << run.err;
}

TEST_F(Cli, UnknownCommandIsAnError) {
  const Outcome run = plumb("teleport");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("teleport"), std::string::npos) << run.err;
}

TEST_F(Cli, BadArgumentsNameTheOption) {
  struct Case {
    std::string arguments, expected;
  };
  const std::string out = " -o " + path("x.ply");
  for (const Case& c :
       {Case{"simulate --points abc" + out, "--points"}, Case{"simulate --noise-mm nan" + out, "nan"},
        Case{"simulate --noise-mm -1" + out, "--noise-mm"},
        Case{"simulate --points 1000 --step-deg 0.1" + out, "--step-deg"},
        Case{"simulate --offset 1,2" + out, "--offset"}, Case{"simulate --offset 1,2,inf" + out, "--offset"},
        Case{"simulate --scene castle" + out, "castle"}, Case{"simulate --points 1000", "--output"},
        Case{"simulate --stations 7" + out, "7 were asked for"}}) {
    const Outcome run = plumb(c.arguments);
    EXPECT_NE(run.exit_code, 0) << c.arguments;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << c.arguments << "\n" << run.err;
    EXPECT_EQ(entries(), 0u) << c.arguments << " left output behind";
  }
}

TEST_F(Cli, SimulateWritesTheRequestedPointsAndTruth) {
  const Outcome run =
      plumb("simulate --scene room --noise-mm 2 --points 200000 --seed 1 --offset 512000,5403000,250 -o " +
            path("room.ply") + " --truth " + path("room.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("points per second"), std::string::npos) << run.out;

  const nlohmann::json truth = nlohmann::json::parse(readAll(path("room.json")));
  const auto written = truth["points"]["written"].get<double>();
  EXPECT_NEAR(written, 200'000.0, 2'000.0);
  const std::string ply = readAll(path("room.ply"));
  EXPECT_NE(ply.find("element vertex " + std::to_string(truth["points"]["written"].get<std::uint64_t>()) + "\n"),
            std::string::npos);
  EXPECT_EQ(truth["offset"][1].get<double>(), 5403000.0);
  EXPECT_EQ(entries(), 2u);
}

TEST_F(Cli, OutputIntoAMissingFolderFailsCleanly) {
  const Outcome run = plumb("simulate --points 1000 -o " + path("nowhere/room.ply"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("nowhere/room.ply"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("plumb simulate: error:"), std::string::npos) << run.err;
  EXPECT_EQ(entries(), 0u);
}

}  // namespace
