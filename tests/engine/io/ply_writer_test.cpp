#include "engine/io/ply_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace plumb::io {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(PlyWriter, WritesAHeaderWithTheFinalCountAndPackedRows) {
  const fs::path path = fs::temp_directory_path() / ("plumb_ply_" + std::to_string(::getpid()) + ".ply");
  const std::vector<PlyProperty> properties{{"x", PlyType::kFloat64},        {"y", PlyType::kFloat64},
                                            {"z", PlyType::kFloat64},        {"red", PlyType::kUInt8},
                                            {"intensity", PlyType::kUInt16}, {"plane_id", PlyType::kUInt32}};
  PlyWriter writer(path.string(), properties, {"made by a test"});
  ASSERT_EQ(writer.rowBytes(), 3 * 8 + 1 + 2 + 4u);

  std::vector<std::byte> rows(writer.rowBytes() * 1234);
  std::byte* out = rows.data();
  for (int i = 0; i < 1234; ++i) {
    out = packLittleEndian(out, 512000.0 + i);
    out = packLittleEndian(out, 5403000.0 - i);
    out = packLittleEndian(out, 250.5);
    out = packLittleEndian(out, static_cast<std::uint8_t>(i));
    out = packLittleEndian(out, static_cast<std::uint16_t>(i * 3));
    out = packLittleEndian(out, static_cast<std::uint32_t>(i * 100000));
  }
  writer.writeRows(std::span(rows).first(writer.rowBytes() * 1000));
  writer.writeRows(std::span(rows).subspan(writer.rowBytes() * 1000));
  EXPECT_EQ(writer.rowCount(), 1234u);
  writer.finish();
  writer.commit();

  const std::string file = readAll(path);
  const std::size_t end = file.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = file.substr(0, end + 11);
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\ncomment made by a test\n", 0), 0u) << header;
  EXPECT_NE(header.find("\nelement vertex 1234\n"), std::string::npos) << header;
  EXPECT_NE(header.find("property double x\nproperty double y\nproperty double z\nproperty uchar red\n"
                        "property ushort intensity\nproperty uint plane_id\nend_header\n"),
            std::string::npos)
      << header;
  ASSERT_EQ(file.size(), header.size() + rows.size());
  EXPECT_EQ(std::memcmp(file.data() + header.size(), rows.data(), rows.size()), 0);

  double last_x = 0;
  std::memcpy(&last_x, file.data() + header.size() + 1233 * writer.rowBytes(), 8);
  EXPECT_EQ(last_x, 512000.0 + 1233);
  fs::remove(path);
}

TEST(PlyWriter, AnEmptyCloudIsAValidFile) {
  const fs::path path = fs::temp_directory_path() / ("plumb_ply_empty_" + std::to_string(::getpid()) + ".ply");
  PlyWriter writer(path.string(), {{"x", PlyType::kFloat32}}, {});
  writer.finish();
  writer.commit();
  const std::string file = readAll(path);
  EXPECT_NE(file.find("element vertex 0\n"), std::string::npos);
  EXPECT_EQ(file.substr(file.size() - 11), "end_header\n");
  fs::remove(path);
}

TEST(PlyWriter, UncommittedWriterLeavesNoFile) {
  const fs::path path = fs::temp_directory_path() / ("plumb_ply_gone_" + std::to_string(::getpid()) + ".ply");
  {
    PlyWriter writer(path.string(), {{"x", PlyType::kFloat32}}, {});
    const float x = 1.0f;
    writer.writeRows(std::as_bytes(std::span(&x, 1)));
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace plumb::io
