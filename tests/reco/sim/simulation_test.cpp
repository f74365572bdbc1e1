#include "reco/sim/simulation.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/io/point_reader.h"
#include "reco/sim/scan_reader.h"
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
    r.points_path = (directory_ / "room.ply").string();
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
  const std::string ply = test::readFile(r.points_path);
  const std::size_t header_end = ply.find("end_header\n") + 11;
  const std::string header = ply.substr(0, header_end);
  EXPECT_NE(header.find("element vertex " + std::to_string(report.counts.returns) + "\n"), std::string::npos);
  EXPECT_NE(header.find("property double x\n"), std::string::npos);
  EXPECT_NE(header.find("property uint plane_id\n"), std::string::npos);
  constexpr std::size_t kRow = 3 * 8 + 3 + 2 + 4;
  ASSERT_EQ(ply.size(), header_end + report.counts.returns * kRow);
  EXPECT_EQ(report.points_bytes, ply.size());

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
  const std::string ply = test::readFile(r.points_path);
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
  r.points_path = (directory_ / "missing" / "room.ply").string();
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

// The points of a PLY or LAS file of the simulator, in order.
std::vector<io::PointRecord> readAll(const std::string& path) {
  const std::unique_ptr<io::PointReader> reader = io::openPointCloud(path);
  std::vector<io::PointRecord> points;
  io::PointBatch batch;
  while (reader->read(batch, 10'000)) points.insert(points.end(), batch.points.begin(), batch.points.end());
  return points;
}

// A .las output is a LAS 1.2 file that Plumb's reader takes, with the same points as the PLY of
// the same seed (to the 0.1 mm step of its integers) and the bounds of its points in its header.
TEST_F(SimulationTest, WritesLasWithThePointsOfThePly) {
  SimulationRequest r = request(50'000);
  r.offset = Eigen::Vector3d(512000, 5403000, 250);
  r.truth_path.clear();
  const SimulationReport ply_report = simulate(r);
  const std::vector<io::PointRecord> ply = readAll(r.points_path);
  r.points_path = (directory_ / "room.las").string();
  const SimulationReport las_report = simulate(r);
  EXPECT_EQ(las_report.points_bytes, 227 + 26 * las_report.counts.returns);

  const std::unique_ptr<io::PointReader> reader = io::openPointCloud(r.points_path);
  EXPECT_EQ(reader->info().format.rfind("LAS 1.2", 0), 0u) << reader->info().format;
  EXPECT_EQ(reader->info().declared_points, ply_report.counts.returns);
  const std::vector<io::PointRecord> las = readAll(r.points_path);
  ASSERT_EQ(las.size(), ply.size());
  io::Bounds bounds{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
  for (std::size_t i = 0; i < las.size(); ++i) {
    const double xyz[3] = {las[i].x, las[i].y, las[i].z}, truth[3] = {ply[i].x, ply[i].y, ply[i].z};
    for (std::size_t a = 0; a < 3; ++a) {
      ASSERT_NEAR(xyz[a], truth[a], 0.5e-4 + 1e-9) << "point " << i;
      bounds.min[a] = std::min(bounds.min[a], xyz[a]);
      bounds.max[a] = std::max(bounds.max[a], xyz[a]);
    }
    ASSERT_EQ(las[i].rgb, ply[i].rgb) << "point " << i;
    ASSERT_EQ(las[i].intensity, ply[i].intensity) << "point " << i;
  }
  ASSERT_TRUE(reader->info().declared_bounds.has_value());
  EXPECT_EQ(reader->info().declared_bounds->min, bounds.min);
  EXPECT_EQ(reader->info().declared_bounds->max, bounds.max);
}

// What LAS cannot hold is refused before the scan: more points than its 32-bit count, and LAZ,
// which plumb simulate does not compress.
TEST_F(SimulationTest, LasLimitsAreRefusedBeforeScanning) {
  SimulationRequest r = request(5'000'000'000);
  r.points_path = (directory_ / "big.las").string();
  r.truth_path.clear();
  try {
    simulate(r);
    FAIL() << "a LAS of 5 billion points was begun";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("at most 4,294,967,295 points"), std::string::npos) << error.what();
  }
  r = request(1'000);
  r.points_path = (directory_ / "room.laz").string();
  EXPECT_THROW(simulate(r), Error);
  EXPECT_EQ(entries(), 0u);
}

// A ScanReader delivers the scan simulate() writes, point for point, as often as it is opened;
// one dropped halfway stops its scan.
TEST_F(SimulationTest, AScanReaderDeliversTheScanEveryTimeItIsOpened) {
  SimulationRequest r = request(60'000);
  r.truth_path.clear();
  const SimulationReport report = simulate(r);
  const std::vector<io::PointRecord> written = readAll(r.points_path);
  PreparedScan prepared = prepareScan(r);
  prepared.source.counts = std::make_shared<ScanCounts>();
  for (int pass = 0; pass < 2; ++pass) {
    ScanReader reader("room scan", prepared.source);
    std::vector<io::PointRecord> read;
    io::PointBatch batch;
    while (reader.read(batch, 7'777)) read.insert(read.end(), batch.points.begin(), batch.points.end());
    ASSERT_EQ(read.size(), written.size()) << "pass " << pass;
    for (std::size_t i = 0; i < read.size(); ++i) {
      // The PLY keeps floats: the reader's doubles round to them.
      ASSERT_EQ(static_cast<float>(read[i].x), static_cast<float>(written[i].x)) << "point " << i;
      ASSERT_EQ(static_cast<float>(read[i].z), static_cast<float>(written[i].z)) << "point " << i;
      ASSERT_EQ(read[i].rgb, written[i].rgb) << "point " << i;
    }
    EXPECT_EQ(prepared.source.counts->returns, report.counts.returns);
  }
  ScanReader dropped("room scan", prepared.source);
  io::PointBatch batch;
  ASSERT_TRUE(dropped.read(batch, 1'000));
  // Its destructor stops the scan and returns: a hang here is the failure.
}
}  // namespace
}  // namespace plumb::reco::sim
