// Tests of the LAZ reader (the point-wise and the layered LASzip coders) on the reference files in
// ../shared/data/formats (its README says where each comes from). A LAZ with an uncompressed LAS
// twin holding the same points, checked with LASzip 3.5.1 and laz-perf, must decode to the LAS
// file's point records byte for byte, and the same points; one without (a layered file, the COPC
// files) to records whose sha256 the README gives. LASzip's own broken files and copies edited
// here (a moved or missing chunk table, variable chunks, truncation, corrupt chunks and layers,
// edited VLRs) must stop with plumb::Error saying what and where. Each test skips when its file
// is absent.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/io/file_source.h"
#include "engine/io/las_reader.h"
#include "engine/io/laz_chunk_table.h"
#include "engine/io/point_reader.h"
#include "tests/engine/io/laz_test_encoder.h"
#include "tests/engine/io/sha256_for_tests.h"
#include "tests/support/shared_data.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

struct Records {
  std::size_t record_length = 0;
  std::vector<std::byte> bytes;  // every record, in file order
  CloudInfo info;
};

// Every record of a LAS or LAZ file, read in batches of `batch` (odd sizes cross LAZ chunks).
Records readRecords(const std::string& path, std::size_t batch = 7'777) {
  auto reader = openLasRecords(path);
  Records records;
  records.record_length = reader->recordLength();
  records.info = reader->info();
  std::vector<std::byte> some;
  while (reader->readRecords(some, batch) > 0) records.bytes.insert(records.bytes.end(), some.begin(), some.end());
  return records;
}

std::vector<PointRecord> readPoints(const std::string& path, ReadCounts* counts = nullptr) {
  auto reader = openPointCloud(path);
  std::vector<PointRecord> points;
  PointBatch batch;
  while (reader->read(batch, 1'000)) points.insert(points.end(), batch.points.begin(), batch.points.end());
  if (counts) *counts = reader->counts();
  return points;
}

// The message of the plumb::Error that reading all of `path` throws, or "" if it reads.
std::string errorReading(const std::string& path) {
  try {
    readRecords(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

// Where two record blocks first differ, for messages: "record 12 byte 3", or "".
std::string firstDifference(const Records& a, const Records& b) {
  const std::size_t n = std::min(a.bytes.size(), b.bytes.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (a.bytes[i] != b.bytes[i]) {
      return "record " + std::to_string(i / a.record_length) + " byte " + std::to_string(i % a.record_length);
    }
  }
  return a.bytes.size() == b.bytes.size() ? "" : "the lengths";
}

template <typename T>
void put(std::string& bytes, std::size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

template <typename T>
T get(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

// Offset of the laszip VLR's payload in a LAZ file image.
std::size_t laszipPayloadAt(const std::string& file) {
  const std::size_t user_id = file.find("laszip encoded");
  EXPECT_NE(user_id, std::string::npos);
  return user_id - 2 + 54;
}

std::size_t pointOffsetOf(const std::string& file) {
  return get<std::uint32_t>(file, 96);
}

// ---- Pairs -----------------------------------------------------------------------------------

struct Pair {
  const char* laz;
  const char* las;
  std::uint64_t points;
  const char* format;  // the LAZ's CloudInfo::format
};

// Every pair of the README's table: the point-wise coder's, then the layered coder's (LAS 1.4
// point formats 6 to 8).
const Pair kPairs[] = {
    {"laz/point10.las.laz", "las/point10.las", 1'065, "LAZ 1.2 point format 0"},
    {"laz/point-time.las.laz", "las/point-time.las", 1'065, "LAZ 1.2 point format 1"},
    {"laz/point-color.las.laz", "las/point-color.las", 1'065, "LAZ 1.2 point format 2"},
    {"laz/point-color-time.las.laz", "las/point-color-time.las", 1'065, "LAZ 1.2 point format 3"},
    {"laz/extrabytes.laz", "las/extrabytes.las", 1'065, "LAZ 1.2 point format 3"},
    {"laz/point10-1.0.laz", "las/point10-1.0.las", 1, "LAZ 1.0 point format 0"},
    {"laz/no-points-1.3.laz", "las/no-points-1.3.las", 0, "LAZ 1.3 point format 0"},
    {"laz/simple.laz", "las/simple.las", 1'065, "LAZ 1.2 point format 3"},
    {"laz/simple-laszip-compressor-version-1.2r0.laz", "las/simple.las", 1'065, "LAZ 1.2 point format 3"},
    {"laz/laszip-generated_with2bytespadding.laz", "las/simple.las", 1'065, "LAZ 1.2 point format 3"},
    {"laz/liblas-generated.laz", "las/simple.las", 1'065, "LAZ 1.2 point format 3"},
    {"laz/autzen_trim.laz", "las/autzen_trim.las", 110'000, "LAZ 1.2 point format 3"},
    {"laz/point-time-1.4.las.laz", "las/point-time.las", 1'065, "LAZ 1.4 point format 1"},
    // The layered coder (compressor 3).
    {"laz/1_4_w_evlr.laz", "las/1_4_w_evlr.las", 1'000, "LAZ 1.4 point format 6"},
    {"laz/autzen-bmx-2010.laz", "las/autzen-bmx-2010.las", 829, "LAZ 1.4 point format 7"},
    {"laz/append-bug.laz", "las/append-bug.las", 37'805, "LAZ 1.4 point format 8"},
};

class LazPair : public ::testing::TestWithParam<Pair> {};

TEST_P(LazPair, DecodesToTheRecordsAndPointsOfItsLasTwin) {
  const Pair& pair = GetParam();
  PLUMB_REQUIRE_FORMAT_FILE(laz_path, pair.laz);
  PLUMB_REQUIRE_FORMAT_FILE(las_path, pair.las);

  // The raw records, bit for bit: every field, GPS time and extra bytes included.
  const Records laz = readRecords(laz_path);
  const Records las = readRecords(las_path);
  EXPECT_EQ(laz.info.format, pair.format);
  EXPECT_EQ(laz.info.declared_points, pair.points);
  ASSERT_EQ(laz.record_length, las.record_length);
  ASSERT_EQ(laz.bytes.size(), pair.points * las.record_length);
  EXPECT_TRUE(laz.bytes == las.bytes) << "first difference: " << firstDifference(laz, las);

  // The points as Plumb keeps them, field by field.
  ReadCounts counts;
  const std::vector<PointRecord> laz_points = readPoints(laz_path, &counts);
  const std::vector<PointRecord> las_points = readPoints(las_path);
  EXPECT_EQ(counts.delivered, pair.points);
  ASSERT_EQ(laz_points.size(), las_points.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < laz_points.size() && mismatches < 5; ++i) {
    const PointRecord& a = laz_points[i];
    const PointRecord& b = las_points[i];
    const bool same = a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity && a.rgb == b.rgb;
    if (!same) {
      ++mismatches;
      ADD_FAILURE() << "point " << i << ": LAZ (" << a.x << ", " << a.y << ", " << a.z << ") intensity " << a.intensity
                    << ", LAS (" << b.x << ", " << b.y << ", " << b.z << ") intensity " << b.intensity;
    }
  }
  EXPECT_EQ(laz.info.attributes.colour, las.info.attributes.colour);
  EXPECT_EQ(laz.info.ignored_fields, las.info.ignored_fields);
}

std::string pairName(const ::testing::TestParamInfo<Pair>& info) {
  std::string name;
  for (const char* c = info.param.laz + 4; *c != '\0'; ++c)
    name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(LazData, LazPair, ::testing::ValuesIn(kPairs), pairName);

// ---- Files that are refused ------------------------------------------------------------------

TEST(LazData, LaszipsBrokenFilesAreRefusedNamingTheField) {
  // LASzip's data/broken_*.laz: LAS 1.0, the laszip VLR's payload at byte 227 + 54 = 281.
  struct Case {
    const char* file;
    const char* where;
    const char* what;
  };
  const Case cases[] = {
      {"laz/broken_coder.laz", "at byte 283", "coder 15"},
      {"laz/broken_compressor.laz", "at byte 281", "compressor 16"},
      {"laz/broken_type.laz", "at byte 321", "item 2 of the laszip VLR has type 22"},
      {"laz/broken_size.laz", "at byte 319", "POINT10 version 6"},
      {"laz/broken_version.laz", "at byte 319", "POINT10 version 6"},
  };
  for (const Case& c : cases) {
    PLUMB_REQUIRE_FORMAT_FILE(path, c.file);
    const std::string message = errorReading(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(c.where), std::string::npos) << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << message;
  }
}

// ---- Layered files without a LAS twin: the README's sha256 of the decoded records ------------

TEST(LazData, TheTestSha256MatchesFips180Examples) {
  const std::string abc = "abc";
  EXPECT_EQ(test::sha256Hex(std::as_bytes(std::span(abc))),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const std::string two_blocks = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  EXPECT_EQ(test::sha256Hex(std::as_bytes(std::span(two_blocks))),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

struct Hashed {
  const char* laz;
  std::uint64_t points;
  std::size_t record_length;
  const char* format;
  const char* sha256;  // of the decoded records, from the README
};

// Layered, fixed chunks of 50 000 (14 chunks), and every COPC file (layered, variable chunks),
// read sequentially as plain LAZ.
const Hashed kHashed[] = {
    {"laz/las_with_several_extra_byte_bloc.laz", 697'721, 41, "LAZ 1.4 point format 8",
     "c19b99bc99062598ede4bed3bc6648832211f51b80ac22c8095cb547d8836406"},
    {"copc/1.2-with-color.copc.laz", 1'065, 36, "LAZ 1.4 point format 7",
     "361eda6829430490b1bba3a2665408642d16211f6c349b2f11edf451c8164422"},
    {"copc/simple_with_page.copc.laz", 1'065, 36, "LAZ 1.4 point format 7",
     "361eda6829430490b1bba3a2665408642d16211f6c349b2f11edf451c8164422"},
    {"copc/autzen.copc.laz", 107, 36, "LAZ 1.4 point format 7",
     "4207ec2b64218878bc7a37e7e004c7f8934668593609a8d4864651b7e1409c99"},
    // PDAL's tindex clips: the only files whose points leave scanner channel 0 (POINT14 v3's
    // context for the RGB14 item flips between channels 1 and 0).
    {"copc/autzen_clip_4326.copc.laz", 28, 36, "LAZ 1.4 point format 7",
     "3251ccc679e04bd7a5ef72bd2bedda6b0ce0d8f29e38b444666001c633792a79"},
    {"copc/autzen_clip_native.copc.laz", 43, 36, "LAZ 1.4 point format 7",
     "7ac65a4ee0e592bd4f74b72e46f94c501764716a8b5908b26e6088f669ff8193"},
    {"copc/lone-star.copc.laz", 518'862, 30, "LAZ 1.4 point format 6",
     "fb81e03fca9a6e3569feb6aa6e9eb92ddbca58ac10cb29fc8ba5e7eec4027dd3"},
};

class LazHashed : public ::testing::TestWithParam<Hashed> {};

TEST_P(LazHashed, DecodesToTheRecordsWhoseSha256TheReadmeGives) {
  const Hashed& file = GetParam();
  PLUMB_REQUIRE_FORMAT_FILE(path, file.laz);
  const Records laz = readRecords(path);
  EXPECT_EQ(laz.info.format, file.format);
  EXPECT_EQ(laz.info.declared_points, file.points);
  ASSERT_EQ(laz.record_length, file.record_length);
  ASSERT_EQ(laz.bytes.size(), file.points * file.record_length);
  EXPECT_EQ(test::sha256Hex(laz.bytes), file.sha256);

  ReadCounts counts;
  const std::vector<PointRecord> points = readPoints(path, &counts);
  EXPECT_EQ(counts.delivered, file.points);
  EXPECT_EQ(points.size(), file.points);
}

std::string hashedName(const ::testing::TestParamInfo<Hashed>& info) {
  std::string name;
  for (const char* c = info.param.laz; *c != '\0'; ++c)
    name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(LazData, LazHashed, ::testing::ValuesIn(kHashed), hashedName);

TEST(LazData, CopcFilesHoldTheSamePointsAsTheirLasSource) {
  // The README: both COPC files hold the multiset of points of las/simple.las, in octree order.
  PLUMB_REQUIRE_FORMAT_FILE(las_path, "las/simple.las");
  // Millimetres: the files' scales and offsets differ, so the doubles may differ in their last bits.
  const auto key = [](const PointRecord& p) {
    return std::tuple(std::llround(p.x * 1e3), std::llround(p.y * 1e3), std::llround(p.z * 1e3), p.intensity, p.rgb);
  };
  const auto sorted = [&](const std::string& path) {
    std::vector<PointRecord> points = readPoints(path);
    std::sort(points.begin(), points.end(), [&](const PointRecord& a, const PointRecord& b) { return key(a) < key(b); });
    return points;
  };
  const std::vector<PointRecord> las = sorted(las_path);
  for (const char* file : {"copc/1.2-with-color.copc.laz", "copc/simple_with_page.copc.laz"}) {
    PLUMB_REQUIRE_FORMAT_FILE(path, file);
    const std::vector<PointRecord> copc = sorted(path);
    ASSERT_EQ(copc.size(), las.size()) << file;
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < las.size(); ++i) mismatches += key(copc[i]) == key(las[i]) ? 0u : 1u;
    EXPECT_EQ(mismatches, 0u) << file;
  }
}

// ---- Edited copies of autzen_trim.laz (3 chunks of 50 000, 50 000 and 10 000 points) ---------

class LazEdited : public ::testing::Test {
 protected:
  void SetUp() override {
    laz_path_ = test::sharedFormatFile("laz/autzen_trim.laz");
    las_path_ = test::sharedFormatFile("las/autzen_trim.las");
    if (laz_path_.empty() || las_path_.empty()) PLUMB_SHARED_DATA_MISSING("laz/autzen_trim.laz or its LAS twin not found");
    file_ = test::readFile(laz_path_);
    point_offset_ = pointOffsetOf(file_);
    table_offset_ = get<std::uint64_t>(file_, point_offset_);
  }

  std::string write(const std::string& bytes) { return dir_.write("edited.laz", bytes); }

  void expectTheLasRecords(const std::string& path) {
    const Records laz = readRecords(path);
    const Records las = readRecords(las_path_);
    EXPECT_TRUE(laz.bytes == las.bytes) << "first difference: " << firstDifference(laz, las);
  }

  // The chunks as the file's table lists them.
  std::vector<LazChunk> chunks() {
    FileSource source(laz_path_);
    return readLazChunkTable(source, point_offset_, 50'000, 34, 110'000).chunks;
  }

  // The file with its table replaced by one of variable chunks: `points` and `bytes` per chunk.
  std::string withVariableTable(const std::vector<std::uint32_t>& points, const std::vector<std::uint32_t>& bytes) {
    std::string file = file_.substr(0, table_offset_);
    put<std::uint32_t>(file, laszipPayloadAt(file) + 12, 0xFFFFFFFFu);  // chunk size: variable
    std::string table(8, '\0');
    put<std::uint32_t>(table, 4, static_cast<std::uint32_t>(points.size()));
    test::TestRangeEncoder encoder;
    test::TestIntegerCompressor entries(32, 2);
    std::int32_t last_points = 0, last_bytes = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      entries.compress(encoder, last_points, static_cast<std::int32_t>(points[i]), 0);
      entries.compress(encoder, last_bytes, static_cast<std::int32_t>(bytes[i]), 1);
      last_points = static_cast<std::int32_t>(points[i]);
      last_bytes = static_cast<std::int32_t>(bytes[i]);
    }
    for (const std::uint8_t byte : encoder.finish()) table += static_cast<char>(byte);
    return file + table;
  }

  test::TempDirectory dir_;
  std::string laz_path_, las_path_;
  std::string file_;
  std::size_t point_offset_ = 0;
  std::uint64_t table_offset_ = 0;
};

TEST_F(LazEdited, AChunkTableStoredAtTheEndOfTheFileIsFound) {
  // A writer that could not seek back: -1 at the start of the point data, the offset at the end.
  std::string file = file_;
  put<std::int64_t>(file, point_offset_, -1);
  file.append(8, '\0');
  put<std::uint64_t>(file, file.size() - 8, table_offset_);
  expectTheLasRecords(write(file));
}

TEST_F(LazEdited, WithoutAChunkTableFixedChunksAreReadOneAfterAnother) {
  // An interrupted writer leaves the table's offset pointing at itself: each chunk then starts
  // where the previous one's compressed data ended, which holds only when the decoder reads
  // exactly the bytes the encoder wrote.
  std::string file = file_;
  put<std::uint64_t>(file, point_offset_, point_offset_);
  expectTheLasRecords(write(file));
}

TEST_F(LazEdited, VariableChunksFollowTheTablesPointCounts) {
  const std::vector<LazChunk> listed = chunks();
  ASSERT_EQ(listed.size(), 3u);
  std::vector<std::uint32_t> bytes;
  for (const LazChunk& chunk : listed) bytes.push_back(static_cast<std::uint32_t>(chunk.bytes));
  expectTheLasRecords(write(withVariableTable({50'000, 50'000, 10'000}, bytes)));

  // A table that holds one point too few.
  const std::string message = errorReading(write(withVariableTable({50'000, 50'000, 9'999}, bytes)));
  EXPECT_NE(message.find("hold 109999 points, where the header declares 110000"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte " + std::to_string(table_offset_ + 4)), std::string::npos) << message;
}

TEST_F(LazEdited, AChunkThatRunsPastTheTableIsRefused) {
  std::vector<std::uint32_t> bytes;
  for (const LazChunk& chunk : chunks()) bytes.push_back(static_cast<std::uint32_t>(chunk.bytes));
  bytes[1] += 1'000'000;
  const std::string message = errorReading(write(withVariableTable({50'000, 50'000, 10'000}, bytes)));
  EXPECT_NE(message.find("chunk 2 of 3"), std::string::npos) << message;
  EXPECT_NE(message.find("runs past the chunk table"), std::string::npos) << message;
}

TEST_F(LazEdited, ATruncatedFileLosesItsChunkTable) {
  const std::string message = errorReading(write(file_.substr(0, 400'000)));
  EXPECT_NE(message.find("at byte " + std::to_string(point_offset_)), std::string::npos) << message;
  EXPECT_NE(message.find("the chunk table's offset 603333 points outside"), std::string::npos) << message;
}

TEST_F(LazEdited, AChunkTableOffsetPastTheEndIsRefused) {
  std::string file = file_;
  put<std::uint64_t>(file, point_offset_, file.size() + 100);
  const std::string message = errorReading(write(file));
  EXPECT_NE(message.find("at byte " + std::to_string(point_offset_)), std::string::npos) << message;
  EXPECT_NE(message.find("chunk table"), std::string::npos) << message;
}

TEST_F(LazEdited, ATruncatedChunkStopsWhereItsBytesEnd) {
  // No table to catch the truncation first: the decoder runs out of bytes in the second chunk.
  const std::vector<LazChunk> listed = chunks();
  ASSERT_EQ(listed.size(), 3u);
  const std::uint64_t cut = listed[1].offset + listed[1].bytes / 2;
  std::string file = file_.substr(0, cut);
  put<std::uint64_t>(file, point_offset_, point_offset_);
  const std::string message = errorReading(write(file));
  EXPECT_NE(message.find("at byte " + std::to_string(cut)), std::string::npos) << message;
  EXPECT_NE(message.find("truncated or corrupt LAZ data: chunk 2"), std::string::npos) << message;
}

TEST_F(LazEdited, ATruncatedChunkInParallelStopsAsTheSequentialDecoder) {
  // The table kept, chunk 2 cut to half its bytes (chunk 3 then starts inside it): chunk 2 fails
  // when its bytes end, after the 50 000 records of chunk 1 and those of chunk 2 before the failure,
  // with the same message however many chunks are in flight.
  const std::vector<LazChunk> listed = chunks();
  ASSERT_EQ(listed.size(), 3u);
  const auto half = static_cast<std::uint32_t>(listed[1].bytes / 2);
  const auto first = static_cast<std::uint32_t>(listed[0].bytes);
  const auto last = static_cast<std::uint32_t>(listed[2].bytes);
  const std::string path = write(withVariableTable({50'000, 50'000, 10'000}, {first, half, last}));
  const auto outcome = [&](std::size_t in_flight) {
    auto reader = openLasRecords(path, LasReadOptions{.laz_chunks_in_flight = in_flight});
    std::size_t handed = 0;
    std::vector<std::byte> some;
    try {
      while (const std::size_t n = reader->readRecords(some, 1'000)) handed += n;
    } catch (const Error& error) {
      return std::pair(handed, std::string(error.what()));
    }
    return std::pair(handed, std::string());
  };
  const auto [sequential_handed, sequential_error] = outcome(1);
  EXPECT_GT(sequential_handed, 50'000u);
  EXPECT_LT(sequential_handed, 100'000u);
  EXPECT_NE(sequential_error.find("at byte " + std::to_string(listed[1].offset + half)), std::string::npos)
      << sequential_error;
  EXPECT_NE(sequential_error.find("truncated or corrupt LAZ data: chunk 2 of 3"), std::string::npos)
      << sequential_error;
  for (const std::size_t in_flight : {std::size_t{0}, std::size_t{2}, std::size_t{3}}) {
    EXPECT_EQ(outcome(in_flight), std::pair(sequential_handed, sequential_error)) << in_flight << " in flight";
  }
}

TEST_F(LazEdited, CorruptChunksEndInAnErrorOrInOtherPoints) {
  // Garbage in the middle of chunk 2: the decoder must never crash or read outside its chunk
  // (ASan and UBSan builds run this too); it either runs out of the chunk's bytes or decodes other
  // points.
  const std::vector<LazChunk> listed = chunks();
  ASSERT_EQ(listed.size(), 3u);
  const Records las = readRecords(las_path_);
  std::mt19937 random(20240601);
  int errors = 0;
  for (int trial = 0; trial < 6; ++trial) {
    std::string file = file_;
    std::uniform_int_distribution<std::uint64_t> where(listed[1].offset + 34, listed[1].offset + listed[1].bytes - 64);
    const std::uint64_t at = where(random);
    for (std::uint64_t i = at; i < at + 64; ++i) file[i] = static_cast<char>(random());
    try {
      const Records laz = readRecords(write(file));
      EXPECT_FALSE(laz.bytes == las.bytes) << "garbage at byte " << at << " decoded to the original points";
    } catch (const Error& error) {
      ++errors;
      EXPECT_NE(std::string(error.what()).find("chunk 2 of 3"), std::string::npos) << error.what();
    }
  }
  std::cout << "corrupt chunks: " << errors << " of 6 ended in an error\n";
}

// ---- Edited laszip VLRs of simple.laz (LAS 1.2 point format 3) -------------------------------

class LazEditedVlr : public ::testing::Test {
 protected:
  void SetUp() override {
    laz_path_ = test::sharedFormatFile("laz/simple.laz");
    if (laz_path_.empty()) PLUMB_SHARED_DATA_MISSING("laz/simple.laz not found");
    file_ = test::readFile(laz_path_);
    payload_at_ = laszipPayloadAt(file_);
  }

  std::string errorOf(const std::string& bytes) { return errorReading(dir_.write("edited.laz", bytes)); }

  test::TempDirectory dir_;
  std::string laz_path_, file_;
  std::size_t payload_at_ = 0;
};

TEST_F(LazEditedVlr, TheVlrDecidesEvenWithoutTheFormatBits) {
  // As in LASzip: a file with the laszip VLR is compressed, whatever the format byte says.
  std::string file = file_;
  file[104] = 3;
  const std::string path = dir_.write("no-bits.laz", file);
  EXPECT_TRUE(readRecords(path).bytes == readRecords(laz_path_).bytes);
}

TEST_F(LazEditedVlr, FormatBitsWithoutTheVlrAreRefused) {
  std::string file = file_;
  file[payload_at_ - 54 + 2] = 'X';  // "Xaszip encoded"
  const std::string message = errorOf(file);
  EXPECT_NE(message.find("at byte 104"), std::string::npos) << message;
  EXPECT_NE(message.find("no laszip VLR"), std::string::npos) << message;
}

TEST_F(LazEditedVlr, UnsupportedCompressorsItemsAndVersionsAreNamed) {
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_, 3);
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("at byte " + std::to_string(payload_at_ + 34)), std::string::npos) << message;
    EXPECT_NE(message.find("which the layered coder (compressor 3) does not code"), std::string::npos) << message;
  }
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ + 34 + 12 + 4, 0);  // RGB12, version 0
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("at byte " + std::to_string(payload_at_ + 50)), std::string::npos) << message;
    EXPECT_NE(message.find("item 3 of the laszip VLR is RGB12 version 0"), std::string::npos) << message;
  }
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ + 34 + 6, 9);  // GPSTIME11 becomes WAVEPACKET13
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("WAVEPACKET13"), std::string::npos) << message;
  }
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ + 34 + 6 + 2, 9);  // GPSTIME11 of 9 bytes
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("GPSTIME11 of 9 bytes"), std::string::npos) << message;
  }
  {
    // Point format 1 with 34-byte records is POINT10, GPSTIME11 and 6 extra bytes, not RGB12.
    std::string file = file_;
    file[104] = static_cast<char>(0x81);
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("are not the records of point format 1 with 34 bytes"), std::string::npos) << message;
    EXPECT_NE(message.find("BYTE (6 bytes)"), std::string::npos) << message;
  }
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ - 54 + 20, 33);  // the VLR's length: not 34 + 6 per item
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("the laszip VLR has 33 bytes"), std::string::npos) << message;
  }
}

// ---- Edited copies of autzen-bmx-2010.laz (layered, point format 7, 5 chunks of 200) ----------

// Chunk 1 starts 8 bytes after the point offset: the first point raw (36 bytes), the chunk's point
// count (u32), then 10 layer sizes (u32: POINT14's nine, RGB14's one), then the layers.
class LazEditedLayered : public ::testing::Test {
 protected:
  void SetUp() override {
    laz_path_ = test::sharedFormatFile("laz/autzen-bmx-2010.laz");
    if (laz_path_.empty()) PLUMB_SHARED_DATA_MISSING("laz/autzen-bmx-2010.laz not found");
    file_ = test::readFile(laz_path_);
    payload_at_ = laszipPayloadAt(file_);
    count_at_ = pointOffsetOf(file_) + 8 + 36;
    sizes_at_ = count_at_ + 4;
  }

  std::string errorOf(const std::string& bytes) {
    path_ = dir_.write("edited.laz", bytes);
    return errorReading(path_);
  }

  test::TempDirectory dir_;
  std::string laz_path_, file_, path_;
  std::size_t payload_at_ = 0, count_at_ = 0, sizes_at_ = 0;
};

TEST_F(LazEditedLayered, ALayerRunningPastItsChunkIsNamed) {
  std::string file = file_;
  put<std::uint32_t>(file, sizes_at_ + 4, 0x7FFFFFFFu);  // the z layer
  const std::string message = errorOf(file);
  EXPECT_NE(message.find(path_), std::string::npos) << message;
  EXPECT_NE(message.find("at byte " + std::to_string(sizes_at_ + 4)), std::string::npos) << message;
  EXPECT_NE(message.find("layer POINT14 z of chunk 1 of 5"), std::string::npos) << message;
  EXPECT_NE(message.find("past the chunk's end"), std::string::npos) << message;
}

TEST_F(LazEditedLayered, ATruncatedLayerStopsWhereItsBytesEnd) {
  std::string file = file_;
  put<std::uint32_t>(file, sizes_at_, 2);  // x/y: 2 bytes, fewer than the decoder's first 4
  const std::string message = errorOf(file);
  EXPECT_NE(message.find(path_), std::string::npos) << message;
  EXPECT_NE(message.find("at byte " + std::to_string(sizes_at_ + 40 + 2)), std::string::npos) << message;
  EXPECT_NE(message.find("layer POINT14 x/y and returns of chunk 1 of 5"), std::string::npos) << message;
  EXPECT_NE(message.find("needs more bytes than it has"), std::string::npos) << message;
}

TEST_F(LazEditedLayered, AnEmptyCoordinateLayerIsRefused) {
  std::string file = file_;
  put<std::uint32_t>(file, sizes_at_, 0);
  const std::string message = errorOf(file);
  EXPECT_NE(message.find("at byte " + std::to_string(sizes_at_)), std::string::npos) << message;
  EXPECT_NE(message.find("is empty, but the chunk has 200 points"), std::string::npos) << message;
}

TEST_F(LazEditedLayered, AChunkHoldingFewerPointsThanItsTableSaysIsRefused) {
  std::string file = file_;
  put<std::uint32_t>(file, count_at_, 5);
  const std::string message = errorOf(file);
  EXPECT_NE(message.find("at byte " + std::to_string(count_at_)), std::string::npos) << message;
  EXPECT_NE(message.find("says it holds 5 points, where 200 are read from it"), std::string::npos) << message;
}

TEST_F(LazEditedLayered, ATruncatedFileIsRefused) {
  // Cut inside chunk 3: the chunk table at the end is gone with it.
  const std::string message = errorOf(file_.substr(0, pointOffsetOf(file_) + (file_.size() - pointOffsetOf(file_)) / 2));
  EXPECT_NE(message.find(path_), std::string::npos) << message;
  EXPECT_NE(message.find("chunk table"), std::string::npos) << message;
}

TEST_F(LazEditedLayered, UnknownVersionsAndWaveformItemsAreNamed) {
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ + 34 + 4, 5);  // POINT14 version 5
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("at byte " + std::to_string(payload_at_ + 38)), std::string::npos) << message;
    EXPECT_NE(message.find("POINT14 version 5: the layered LAZ coder has versions 3 and 4"), std::string::npos)
        << message;
  }
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ + 34 + 6, 13);  // RGB14 becomes WAVEPACKET14
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("at byte " + std::to_string(payload_at_ + 40)), std::string::npos) << message;
    EXPECT_NE(message.find("WAVEPACKET14: waveform packets"), std::string::npos) << message;
  }
  {
    std::string file = file_;
    put<std::uint16_t>(file, payload_at_ + 34 + 6 + 2, 8);  // RGB14 of 8 bytes
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("RGB14 of 8 bytes"), std::string::npos) << message;
  }
  {
    // Point format 6 with 36-byte records is POINT14 and 6 extra bytes, not RGB14.
    std::string file = file_;
    file[104] = static_cast<char>(0x86);
    const std::string message = errorOf(file);
    EXPECT_NE(message.find("are not the records of point format 6 with 36 bytes"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace plumb::io
