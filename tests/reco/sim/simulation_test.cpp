#include "reco/sim/simulation.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "tests/support/temp_directory.h"

namespace plumb::reco::sim {
namespace {

namespace fs = std::filesystem;

class SimulationTest : public ::testing::Test {
 protected:
  SimulationRequest request(std::uint64_t points) const {
    SimulationRequest r;
    r.scene = "room";
    r.target_points = points;
    r.ply_path = (directory_ / "room.ply").string();
    r.truth_path = (directory_ / "room.json").string();
    return r;
  }
  std::size_t entries() const { return temp_.entryCount(); }

  test::TempDirectory temp_;
  fs::path directory_ = temp_.path();
};

TEST_F(SimulationTest, WritesDoublePrecisionPlyAndTruthAtAnOffset) {
  SimulationRequest r = request(100'000);
  r.offset = Eigen::Vector3d(512000, 5403000, 250);
  r.scanner.noise_m = 0.002;
  const SimulationReport report = simulate(r);

  EXPECT_NEAR(static_cast<double>(report.counts.returns), 100'000.0, 1'000.0);
  const std::string ply = test::readFile(r.ply_path);
  const std::size_t header_end = ply.find("end_header\n") + 11;
  const std::string header = ply.substr(0, header_end);
  EXPECT_NE(header.find("element vertex " + std::to_string(report.counts.returns) + "\n"), std::string::npos);
  EXPECT_NE(header.find("property double x\n"), std::string::npos);
  EXPECT_NE(header.find("property uint plane_id\n"), std::string::npos);
  constexpr std::size_t kRow = 3 * 8 + 3 + 2 + 4;
  ASSERT_EQ(ply.size(), header_end + report.counts.returns * kRow);
  EXPECT_EQ(report.ply_bytes, ply.size());

  const nlohmann::json truth = nlohmann::json::parse(test::readFile(r.truth_path));
  EXPECT_EQ(truth["format"], "plumb-simulation-truth");
  EXPECT_EQ(truth["points"]["written"], report.counts.returns);
  ASSERT_EQ(truth["planes"].size(), report.planes);
  ASSERT_EQ(truth["corners"].size(), report.corners);
  ASSERT_EQ(truth["edges"].size(), report.edges);

  // Every point lies near the true plane it names, in world coordinates with the offset.
  const auto& planes = truth["planes"];
  double sum_squares = 0.0;
  for (std::uint64_t i = 0; i < report.counts.returns; ++i) {
    double xyz[3];
    std::uint32_t plane_id;
    std::memcpy(xyz, ply.data() + header_end + i * kRow, sizeof xyz);
    std::memcpy(&plane_id, ply.data() + header_end + i * kRow + kRow - 4, sizeof plane_id);
    ASSERT_LT(plane_id, planes.size());
    const auto& plane = planes[plane_id];
    const double d = plane["normal"][0].get<double>() * xyz[0] + plane["normal"][1].get<double>() * xyz[1] +
                     plane["normal"][2].get<double>() * xyz[2] + plane["d"].get<double>();
    sum_squares += d * d;
  }
  EXPECT_NEAR(std::sqrt(sum_squares / static_cast<double>(report.counts.returns)), 0.002, 0.0002);

  // Corners in world coordinates satisfy their planes' equations.
  for (const auto& corner : truth["corners"]) {
    const Eigen::Vector3d x(corner["position"][0].get<double>(), corner["position"][1].get<double>(),
                            corner["position"][2].get<double>());
    EXPECT_GT(x.x(), 511990.0);
    for (const auto& id : corner["planes"]) {
      const auto& plane = planes[id.get<std::size_t>()];
      const Eigen::Vector3d n(plane["normal"][0].get<double>(), plane["normal"][1].get<double>(),
                              plane["normal"][2].get<double>());
      EXPECT_NEAR(n.dot(x) + plane["d"].get<double>(), 0.0, 1e-8);
    }
  }
}

TEST_F(SimulationTest, WithoutOffsetCoordinatesAreFloats) {
  SimulationRequest r = request(10'000);
  r.truth_path.clear();
  const SimulationReport report = simulate(r);
  const std::string ply = test::readFile(r.ply_path);
  EXPECT_NE(ply.find("property float x\n"), std::string::npos);
  EXPECT_EQ(ply.size(), ply.find("end_header\n") + 11 + report.counts.returns * (3 * 4 + 3 + 2 + 4));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(SimulationTest, AnExplicitPatternIsUsedAsGiven) {
  SimulationRequest r = request(1);
  r.target_points.reset();
  r.scanner.pattern = ScanPattern::fromStep(2.0);
  const SimulationReport report = simulate(r);
  EXPECT_EQ(report.pattern.columns, 180u);
  EXPECT_EQ(report.pattern.rows, 75u);
  EXPECT_EQ(report.counts.rays, 180u * 75u);
}

TEST_F(SimulationTest, MissingOutputFolderFailsBeforeScanningAndLeavesNothing) {
  SimulationRequest r = request(10'000);
  r.ply_path = (directory_ / "missing" / "room.ply").string();
  EXPECT_THROW(simulate(r), Error);
  EXPECT_EQ(entries(), 0u);
}

TEST_F(SimulationTest, UnwritableTruthLeavesNoPointCloud) {
  SimulationRequest r = request(10'000);
  r.truth_path = (directory_ / "missing" / "room.json").string();
  EXPECT_THROW(simulate(r), Error);
  EXPECT_EQ(entries(), 0u);
}

TEST_F(SimulationTest, ImpossibleRequestsAreErrors) {
  SimulationRequest r = request(10'000);
  r.station_count = 9;
  EXPECT_THROW(simulate(r), Error);
  r = request(0);
  EXPECT_THROW(simulate(r), Error);
  r = request(kMaxSimulatedPoints + 1);
  EXPECT_THROW(simulate(r), Error);
  r = request(10'000);
  r.scene = "castle";
  EXPECT_THROW(simulate(r), Error);
  EXPECT_EQ(entries(), 0u);
}

TEST_F(SimulationTest, DiskSpaceIsCheckedUpFront) {
  // 20 billion points would need hundreds of gigabytes: refused before any work.
  if (fs::space(directory_).available > (std::uint64_t{1} << 40)) GTEST_SKIP() << "more than 1 TiB free here";
  SimulationRequest r = request(kMaxSimulatedPoints);
  try {
    simulate(r);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("GiB"), std::string::npos) << error.what();
  }
  EXPECT_EQ(entries(), 0u);
}

}  // namespace
}  // namespace plumb::reco::sim
