#include "tests/support/simulated_truth.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/core/error.h"
#include "engine/io/byte_order.h"
#include "reco/edges_and_corners.h"

namespace plumb::test {

std::vector<reco::PlaneRegression> fitTruePlanes(
    const std::string& path, std::size_t plane_count, const Eigen::Vector3d& reference,
    const std::function<void(const Eigen::Vector3d&, std::uint32_t)>& each_point) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw fileError(path, "cannot open the simulated scan");
  std::string line;
  std::uint64_t vertices = 0;
  std::size_t row_bytes = 0;
  struct Field {
    std::size_t offset;
    std::string type;
  };
  std::map<std::string, Field> fields;
  bool binary_le = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string format;
      words >> format;
      binary_le = format == "binary_little_endian";
    } else if (keyword == "element") {
      std::string name;
      words >> name >> vertices;
      if (name != "vertex") throw fileError(path, "expected only a vertex element, found '" + name + "'");
    } else if (keyword == "property") {
      std::string type, name;
      words >> type >> name;
      static const std::map<std::string, std::size_t> kSizes{
          {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
          {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
          {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
      const auto size = kSizes.find(type);
      if (size == kSizes.end()) throw fileError(path, "unexpected property type '" + type + "'");
      fields[name] = {row_bytes, type};
      row_bytes += size->second;
    }
  }
  if (!in || !binary_le) throw fileError(path, "not a binary little-endian PLY as plumb simulate writes");
  for (const char* name : {"x", "y", "z", "plane_id"}) {
    if (!fields.contains(name)) throw fileError(path, std::string("has no property '") + name + "'");
  }
  const auto coordinate = [&](const std::byte* row, const Field& field) {
    return field.type == "double" || field.type == "float64"
               ? io::loadLittleEndian<double>(row + field.offset)
               : static_cast<double>(io::loadLittleEndian<float>(row + field.offset));
  };
  const Field x = fields["x"], y = fields["y"], z = fields["z"], plane_id = fields["plane_id"];
  if (plane_id.type != "uint" && plane_id.type != "uint32") throw fileError(path, "plane_id is not a uint");

  std::vector<reco::PlaneRegression> regressions(plane_count, reco::PlaneRegression::withReference(reference));
  constexpr std::uint64_t kBatchRows = 65536;
  std::vector<std::byte> rows(kBatchRows * row_bytes);
  const auto data_offset = static_cast<std::uint64_t>(in.tellg());
  for (std::uint64_t done = 0; done < vertices;) {
    const std::uint64_t count = std::min(kBatchRows, vertices - done);
    in.read(reinterpret_cast<char*>(rows.data()), static_cast<std::streamsize>(count * row_bytes));
    if (!in) throw fileErrorAt(path, data_offset + done * row_bytes, "truncated vertex data in these rows");
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::byte* row = rows.data() + i * row_bytes;
      const auto id = io::loadLittleEndian<std::uint32_t>(row + plane_id.offset);
      if (id >= plane_count) throw fileError(path, "plane_id " + std::to_string(id) + " is not in the truth");
      const Eigen::Vector3d p(coordinate(row, x), coordinate(row, y), coordinate(row, z));
      regressions[id].add(p);
      if (each_point) each_point(p, id);
    }
    done += count;
  }
  return regressions;
}

namespace {

// The covariance's eigen decomposition: eigenvalues ascending, so the first is the normal's
// (the residual variance) and the other two the in-plane spreads.
Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(const reco::PlaneRegression& fit) {
  if (fit.count() < 3) throw Error("a plane fit of fewer than 3 points has no standard error");
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(fit.covariance());
}

}  // namespace

double planeStandardErrorAt(const reco::PlaneRegression& fit, const Eigen::Vector3d& point) {
  const auto eigen = spread(fit);
  const double sigma2 = std::max(eigen.eigenvalues()[0], 0.0);
  const auto n = static_cast<double>(fit.count());
  const Eigen::Vector3d offset = point - fit.centroid();
  double variance = sigma2 / n;
  for (int axis = 1; axis < 3; ++axis) {
    const double along = offset.dot(eigen.eigenvectors().col(axis));
    variance += sigma2 * along * along / (n * eigen.eigenvalues()[axis]);
  }
  return std::sqrt(variance);
}

double planeAngleStandardError(const reco::PlaneRegression& fit) {
  const auto eigen = spread(fit);
  const double sigma2 = std::max(eigen.eigenvalues()[0], 0.0);
  const auto n = static_cast<double>(fit.count());
  return std::sqrt(sigma2 / n * (1.0 / eigen.eigenvalues()[1] + 1.0 / eigen.eigenvalues()[2]));
}

double cornerStandardError(const std::array<const reco::PlaneRegression*, 3>& fits, const Eigen::Vector3d& corner) {
  // The corner solves N x = -d for the planes' normals N: an error e_i in plane i's distance
  // moves it by N^-1 e, so its covariance is N^-1 diag(var e) N^-T.
  Eigen::Matrix3d normals;
  Eigen::Vector3d variances;
  for (int i = 0; i < 3; ++i) {
    const reco::PlaneRegression& fit = *fits[static_cast<std::size_t>(i)];
    normals.row(i) = fit.fit().normal.transpose();
    const double error = planeStandardErrorAt(fit, corner);
    variances[i] = error * error;
  }
  const Eigen::Matrix3d inverse = normals.inverse();
  return std::sqrt((inverse * variances.asDiagonal() * inverse.transpose()).trace());
}

namespace {

Eigen::Vector3d vector3(const nlohmann::json& value) {
  return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>()};
}

nlohmann::json readTruth(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw fileError(path, "cannot open the simulation's truth");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& error) {
    throw fileError(path, std::string("not the simulator's truth: ") + error.what());
  }
}

}  // namespace

SimulatedTruth::SimulatedTruth(const std::string& points_path, const std::string& truth_path)
    : truth_path_(truth_path) {
  const nlohmann::json truth = readTruth(truth_path);
  try {
    for (const nlohmann::json& plane : truth.at("planes")) {
      planes_.push_back(
          {plane.at("name").get<std::string>(), vector3(plane.at("normal")), plane.at("d").get<double>()});
    }
    for (const nlohmann::json& corner : truth.at("corners")) {
      const auto ids = corner.at("planes").get<std::array<std::uint32_t, 3>>();
      for (const std::uint32_t id : ids) {
        if (id >= planes_.size()) throw fileError(truth_path, "a corner names a plane the truth does not list");
      }
      corners_.push_back({vector3(corner.at("position")), ids});
    }
  } catch (const nlohmann::json::exception& error) {
    throw fileError(truth_path, std::string("not the simulator's truth: ") + error.what());
  }
  const nlohmann::json& offset = truth.at("offset");
  fits_ = fitTruePlanes(points_path, planes_.size(), vector3(offset));
}

CornerLimit SimulatedTruth::cornerLimit(const Eigen::Vector3d& position) const {
  for (const TrueCorner& corner : corners_) {
    if ((corner.position - position).norm() > 1e-3) continue;
    const std::array<const reco::PlaneRegression*, 3> three{&fits_[corner.planes[0]], &fits_[corner.planes[1]],
                                                            &fits_[corner.planes[2]]};
    const std::optional<Eigen::Vector3d> fitted = reco::cornerOfPlanes(three[0]->fit(), three[1]->fit(), three[2]->fit());
    if (!fitted) throw fileError(truth_path_, "the fitted planes of the corner asked do not meet");
    return {corner.position, *fitted, cornerStandardError(three, corner.position)};
  }
  throw fileError(truth_path_, "has no corner at the position asked");
}

PlaneLimit SimulatedTruth::planeLimit(const std::string& name, const Eigen::Vector3d& point) const {
  for (std::size_t id = 0; id < planes_.size(); ++id) {
    if (planes_[id].name != name) continue;
    return {planes_[id].normal, planes_[id].d, planeStandardErrorAt(fits_[id], point),
            planeAngleStandardError(fits_[id])};
  }
  throw fileError(truth_path_, "has no plane '" + name + "'");
}

}  // namespace plumb::test
