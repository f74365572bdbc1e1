// LAZ tests without ../shared/data: the range decoder and the integer corrector decoding against
// a test encoder (laz_test_encoder.h), and small LAZ files built byte by byte whose chunks hold one
// point each, stored raw, so that no item encoder is needed. The items' arithmetic is checked
// bit for bit against LASzip's output in laz_data_test.cpp.

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/io/file_source.h"
#include "engine/io/las_reader.h"
#include "engine/io/laz_arithmetic_decoder.h"
#include "engine/io/laz_integer_decompressor.h"
#include "engine/io/point_reader.h"
#include "tests/engine/io/laz_test_encoder.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

template <typename T>
void put(std::string& bytes, std::size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

template <typename T>
void append(std::string& bytes, T value) {
  bytes.append(sizeof(T), '\0');
  put(bytes, bytes.size() - sizeof(T), value);
}

std::string asString(const std::vector<std::uint8_t>& bytes) {
  return {bytes.begin(), bytes.end()};
}

// ---- The range decoder and the integer decompressor ------------------------------------------

TEST(LazArithmeticDecoder, DecodesWhatTheEncoderCoded) {
  // Bits of skewed and even probability, symbols of alphabets with and without the decoder's
  // look-up table (more than 16 symbols), raw bits of every width, interleaved at random.
  std::mt19937 random(7);
  std::vector<test::TestBitModel> bit_models(3);
  const std::vector<std::uint32_t> sizes{2, 3, 16, 17, 64, 256, 516, 2048};
  std::vector<test::TestSymbolModel> symbol_models;
  for (std::uint32_t n : sizes) symbol_models.emplace_back(n);

  struct Step {
    int kind;  // 0 bit, 1 symbol, 2 raw bits, 3 raw 64 bits
    std::size_t model;
    unsigned bits;
    std::uint64_t value;
  };
  std::vector<Step> steps;
  test::TestRangeEncoder encoder;
  for (int i = 0; i < 30'000; ++i) {
    Step step{static_cast<int>(random() % 4), 0, 0, 0};
    if (step.kind == 0) {
      step.model = random() % bit_models.size();
      // Model 0 mostly 0, model 1 mostly 1, model 2 even.
      const auto r = static_cast<std::uint32_t>(random() % 100);
      step.value = step.model == 0 ? (r < 95 ? 0 : 1) : step.model == 1 ? (r < 90 ? 1 : 0) : r % 2;
      encoder.encodeBit(bit_models[step.model], static_cast<std::uint32_t>(step.value));
    } else if (step.kind == 1) {
      step.model = random() % symbol_models.size();
      // Skewed towards small symbols, so that the models adapt and the counts get halved.
      const std::uint32_t n = sizes[step.model];
      step.value = std::min<std::uint64_t>(n - 1, (random() % n) * (random() % n) / n);
      encoder.encodeSymbol(symbol_models[step.model], static_cast<std::uint32_t>(step.value));
    } else if (step.kind == 2) {
      step.bits = 1 + static_cast<unsigned>(random() % 32);
      step.value = step.bits == 32 ? random() : random() & ((1u << step.bits) - 1);
      encoder.writeBits(step.bits, static_cast<std::uint32_t>(step.value));
    } else {
      step.value = (std::uint64_t{random()} << 32) | random();
      for (int half = 0; half < 2; ++half) {
        const auto word = static_cast<std::uint32_t>(step.value >> (32 * half));
        encoder.writeBits(16, word & 0xFFFF);
        encoder.writeBits(16, word >> 16);
      }
    }
    steps.push_back(step);
  }
  const std::vector<std::uint8_t> coded = encoder.finish();

  test::TempDirectory dir;
  FileSource source(dir.write("coded.bin", asString(coded)));
  LazByteInput input(source);
  input.reset(0, source.size(), "the test stream");
  LazArithmeticDecoder decoder(input);
  decoder.start();
  std::vector<LazBitModel> bits(3);
  std::vector<LazSymbolModel> symbols;
  for (std::uint32_t n : sizes) symbols.emplace_back(n);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const Step& step = steps[i];
    std::uint64_t value = 0;
    if (step.kind == 0) value = decoder.decodeBit(bits[step.model]);
    if (step.kind == 1) value = decoder.decodeSymbol(symbols[step.model]);
    if (step.kind == 2) value = decoder.readBits(step.bits);
    if (step.kind == 3) value = decoder.readInt64();
    ASSERT_EQ(value, step.value) << "step " << i << " of kind " << step.kind;
  }
  // The decoder reads exactly the bytes the encoder wrote: LAZ chunks follow one another on that.
  EXPECT_EQ(input.offset(), coded.size());
}

TEST(LazIntegerDecompressor, DecodesWhatTheCompressorCoded) {
  struct Field {
    unsigned bits, contexts;
  };
  for (const Field field : {Field{8, 2}, Field{16, 4}, Field{32, 3}}) {
    SCOPED_TRACE(field.bits);
    std::mt19937 random(field.bits);
    const std::int64_t top =
        field.bits == 32 ? std::numeric_limits<std::int32_t>::max() : (std::int64_t{1} << field.bits) - 1;
    const std::int64_t bottom = field.bits == 32 ? std::numeric_limits<std::int32_t>::min() : 0;
    std::uniform_int_distribution<std::int64_t> anywhere(bottom, top);
    struct Value {
      std::int32_t prediction, value;
      unsigned context;
    };
    std::vector<Value> values;
    test::TestRangeEncoder encoder;
    test::TestIntegerCompressor compressor(field.bits, field.contexts);
    std::int64_t previous = bottom / 2 + top / 2;
    for (int i = 0; i < 20'000; ++i) {
      // Mostly small steps from the previous value, some jumps anywhere, and the extremes.
      std::int64_t value = previous + static_cast<std::int64_t>(random() % 7) - 3;
      if (i % 10 == 0) value = anywhere(random);
      if (i % 97 == 0) value = i % 2 ? top : bottom;
      value = std::clamp(value, bottom, top);
      const Value coded{static_cast<std::int32_t>(previous), static_cast<std::int32_t>(value),
                        static_cast<unsigned>(random() % field.contexts)};
      compressor.compress(encoder, coded.prediction, coded.value, coded.context);
      values.push_back(coded);
      previous = value;
    }
    test::TempDirectory dir;
    FileSource source(dir.write("coded.bin", asString(encoder.finish())));
    LazByteInput input(source);
    input.reset(0, source.size(), "the test stream");
    LazArithmeticDecoder decoder(input);
    decoder.start();
    LazIntegerDecompressor decompressor(field.bits, field.contexts);
    decompressor.reset();
    for (std::size_t i = 0; i < values.size(); ++i) {
      ASSERT_EQ(decompressor.decompress(decoder, values[i].prediction, values[i].context), values[i].value) << i;
    }
  }
}

TEST(LazArithmeticDecoder, StopsAtTheEndOfItsBytes) {
  test::TempDirectory dir;
  FileSource source(dir.write("short.bin", std::string("\x12\x34\x56\x78\x9a\xbc", 6)));
  LazByteInput input(source);
  input.reset(0, 5, "chunk 7 of 9");
  LazArithmeticDecoder decoder(input);
  decoder.start();
  std::string message;
  try {
    for (int i = 0; i < 10; ++i) decoder.readBits(16);
  } catch (const Error& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("short.bin' at byte 5: truncated or corrupt LAZ data: chunk 7 of 9"), std::string::npos)
      << message;
}

// ---- Small LAZ files -------------------------------------------------------------------------

constexpr std::array<std::size_t, 4> kStandardBytes{20, 28, 26, 34};
constexpr std::uint16_t kPoint10 = 6, kGpsTime11 = 7, kRgb12 = 8, kByte = 0;

struct Item {
  std::uint16_t type, size, version;
};

// One record of point format `format` (0 to 3) with `extra` extra bytes, distinct per `i`.
std::string record(unsigned format, std::size_t extra, int i) {
  std::string bytes(kStandardBytes[format] + extra, '\0');
  put<std::int32_t>(bytes, 0, 100'000 + 37 * i);
  put<std::int32_t>(bytes, 4, -20'000 - 11 * i);
  put<std::int32_t>(bytes, 8, 3'000 + i);
  put<std::uint16_t>(bytes, 12, static_cast<std::uint16_t>(500 + i));
  bytes[14] = static_cast<char>(0x09);  // return 1 of 1
  bytes[15] = static_cast<char>(2 + i % 3);
  bytes[16] = static_cast<char>(-5 + i);
  put<std::uint16_t>(bytes, 18, static_cast<std::uint16_t>(7 * i));
  std::size_t at = 20;
  if (format == 1 || format == 3) {
    put<double>(bytes, at, 1234.5 + i);
    at += 8;
  }
  if (format == 2 || format == 3) {
    for (int c = 0; c < 3; ++c)
      put<std::uint16_t>(bytes, at + 2 * static_cast<std::size_t>(c), static_cast<std::uint16_t>(1000 * (c + 1) + i));
  }
  for (std::size_t e = 0; e < extra; ++e)
    bytes[kStandardBytes[format] + e] = static_cast<char>(0xE0 + e + static_cast<std::size_t>(i));
  return bytes;
}

std::vector<Item> itemsOf(unsigned format, std::size_t extra, std::uint16_t version) {
  std::vector<Item> items{{kPoint10, 20, version}};
  if (format == 1 || format == 3) items.push_back({kGpsTime11, 8, version});
  if (format == 2 || format == 3) items.push_back({kRgb12, 6, version});
  if (extra > 0) items.push_back({kByte, static_cast<std::uint16_t>(extra), version});
  return items;
}

enum class Table { kAfterChunks, kAtTheEnd, kMissing };

struct LazSpec {
  unsigned format = 3;
  std::size_t extra = 0;
  std::uint8_t format_byte_bits = 0x80;
  std::uint16_t compressor = 2;
  std::uint16_t coder = 0;
  std::uint32_t chunk_size = 1;             // 0xFFFFFFFF: variable
  std::optional<std::vector<Item>> items;   // default: itemsOf(format, extra, 2)
  std::optional<std::uint16_t> vlr_bytes;   // default: 34 + 6 per item
  std::vector<std::string> chunks;          // each a raw first record plus its compressed stream
  std::vector<std::uint32_t> chunk_points;  // listed in a variable table; default 1 per chunk
  std::optional<std::uint32_t> points;      // declared; default: one per chunk
  Table table = Table::kAfterChunks;
  std::uint32_t table_version = 0;
  std::optional<std::uint32_t> table_chunks;  // listed; default: all
};

// A chunk of one point: its record raw, then the 4 bytes an encoder writes for nothing.
std::string onePointChunk(const std::string& record) {
  return record + asString(test::TestRangeEncoder().finish());
}

std::string buildLaz(const LazSpec& spec) {
  const std::vector<Item> items = spec.items.value_or(itemsOf(spec.format, spec.extra, 2));
  const std::size_t record_length = kStandardBytes[spec.format] + spec.extra;
  std::string vlr(34, '\0');
  put<std::uint16_t>(vlr, 0, spec.compressor);
  put<std::uint16_t>(vlr, 2, spec.coder);
  vlr[4] = 2;
  vlr[5] = 2;
  put<std::uint32_t>(vlr, 12, spec.chunk_size);
  put<std::int64_t>(vlr, 16, -1);
  put<std::int64_t>(vlr, 24, -1);
  put<std::uint16_t>(vlr, 32, static_cast<std::uint16_t>(items.size()));
  for (const Item& item : items) {
    append(vlr, item.type);
    append(vlr, item.size);
    append(vlr, item.version);
  }

  std::string file(227, '\0');
  std::memcpy(file.data(), "LASF", 4);
  file[24] = 1;
  file[25] = 2;
  put<std::uint16_t>(file, 94, 227);
  put<std::uint32_t>(file, 100, 1);
  file[104] = static_cast<char>(spec.format | spec.format_byte_bits);
  put<std::uint16_t>(file, 105, static_cast<std::uint16_t>(record_length));
  put<std::uint32_t>(file, 107, spec.points.value_or(static_cast<std::uint32_t>(spec.chunks.size())));
  for (std::size_t axis = 0; axis < 3; ++axis) put<double>(file, 131 + 8 * axis, 0.01);
  std::string header(54, '\0');
  std::memcpy(header.data() + 2, "laszip encoded", 14);
  put<std::uint16_t>(header, 18, 22204);
  put<std::uint16_t>(header, 20, spec.vlr_bytes.value_or(static_cast<std::uint16_t>(vlr.size())));
  file += header + vlr;
  const std::size_t point_offset = file.size();
  put<std::uint32_t>(file, 96, static_cast<std::uint32_t>(point_offset));

  if (spec.compressor == 1) {
    for (const std::string& chunk : spec.chunks) file += chunk;
    return file;
  }
  append<std::int64_t>(file, 0);  // the table's offset, set below
  for (const std::string& chunk : spec.chunks) file += chunk;
  const std::size_t table_at = file.size();
  if (spec.table == Table::kMissing) {
    put<std::int64_t>(file, point_offset, static_cast<std::int64_t>(point_offset));
    return file;
  }
  put<std::int64_t>(file, point_offset, spec.table == Table::kAtTheEnd ? -1 : static_cast<std::int64_t>(table_at));
  append(file, spec.table_version);
  const std::uint32_t listed = spec.table_chunks.value_or(static_cast<std::uint32_t>(spec.chunks.size()));
  append(file, listed);
  test::TestRangeEncoder encoder;
  test::TestIntegerCompressor entries(32, 2);
  std::int32_t last_points = 0, last_bytes = 0;
  for (std::size_t i = 0; i < listed; ++i) {
    if (spec.chunk_size == 0xFFFFFFFFu) {
      const auto points = static_cast<std::int32_t>(i < spec.chunk_points.size() ? spec.chunk_points[i] : 1);
      entries.compress(encoder, last_points, points, 0);
      last_points = points;
    }
    const auto bytes = static_cast<std::int32_t>(i < spec.chunks.size() ? spec.chunks[i].size() : 30);
    entries.compress(encoder, last_bytes, bytes, 1);
    last_bytes = bytes;
  }
  if (listed > 0) file += asString(encoder.finish());
  if (spec.table == Table::kAtTheEnd) append<std::int64_t>(file, static_cast<std::int64_t>(table_at));
  return file;
}

class LazReader : public ::testing::Test {
 protected:
  std::string write(const std::string& bytes) { return dir_.write("cloud.laz", bytes); }

  std::vector<std::byte> records(const std::string& bytes) {
    auto reader = openLasRecords(write(bytes));
    std::vector<std::byte> all, some;
    while (reader->readRecords(some, 2) > 0) all.insert(all.end(), some.begin(), some.end());
    return all;
  }

  // The message of the plumb::Error that opening and reading all of `bytes` throws.
  std::string error(const std::string& bytes) {
    try {
      records(bytes);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "a malformed LAZ file was read";
    return {};
  }

  test::TempDirectory dir_;
};

std::vector<std::byte> concatenated(const std::vector<std::string>& records) {
  std::vector<std::byte> bytes;
  for (const std::string& r : records) {
    for (char c : r) bytes.push_back(static_cast<std::byte>(c));
  }
  return bytes;
}

TEST_F(LazReader, ChunksOfOnePointGiveTheirRawRecords) {
  for (unsigned format = 0; format <= 3; ++format) {
    for (const std::size_t extra : {std::size_t{0}, std::size_t{5}}) {
      SCOPED_TRACE("format " + std::to_string(format) + ", extra bytes " + std::to_string(extra));
      LazSpec spec;
      spec.format = format;
      spec.extra = extra;
      std::vector<std::string> expected;
      for (int i = 0; i < 4; ++i) {
        expected.push_back(record(format, extra, i));
        spec.chunks.push_back(onePointChunk(expected.back()));
      }
      EXPECT_EQ(records(buildLaz(spec)), concatenated(expected));

      const auto reader = openPointCloud(write(buildLaz(spec)));
      EXPECT_EQ(reader->info().format, "LAZ 1.2 point format " + std::to_string(format));
      EXPECT_EQ(reader->info().attributes.colour, format >= 2);
      PointBatch batch;
      ASSERT_TRUE(reader->read(batch, 10));
      ASSERT_EQ(batch.size(), 4u);
      EXPECT_DOUBLE_EQ(batch.points[3].x, (100'000 + 37 * 3) * 0.01);
      EXPECT_DOUBLE_EQ(batch.points[3].y, (-20'000 - 11 * 3) * 0.01);
      EXPECT_EQ(batch.points[3].intensity, 503);
      if (format >= 2) {
        EXPECT_EQ(batch.points[3].rgb, (std::array<std::uint16_t, 3>{1003, 2003, 3003}));
      }
    }
  }
}

// What reading every record of a file gives: the records handed out before it stopped, and the
// plumb::Error that stopped it ("" when none).
struct ReadOutcome {
  std::vector<std::byte> records;
  std::string error;
};

ReadOutcome readAll(const std::string& path, std::size_t chunks_in_flight, std::size_t batch) {
  ReadOutcome outcome;
  try {
    auto reader = openLasRecords(path, LasReadOptions{.laz_chunks_in_flight = chunks_in_flight});
    std::vector<std::byte> some;
    while (reader->readRecords(some, batch) > 0)
      outcome.records.insert(outcome.records.end(), some.begin(), some.end());
  } catch (const Error& e) {
    outcome.error = e.what();
  }
  return outcome;
}

TEST_F(LazReader, ChunksDecodedInParallelComeOutAsTheSequentialDecoderGivesThem) {
  // 40 chunks; then the same with chunk 30 cut to 10 bytes, which the table says it holds: the
  // error must come after the 29 records before it, with the sequential decoder's message.
  LazSpec spec;
  std::vector<std::string> expected;
  for (int i = 0; i < 40; ++i) {
    expected.push_back(record(3, 2, i));
    spec.extra = 2;
    spec.chunks.push_back(onePointChunk(expected.back()));
  }
  const std::string whole = write(buildLaz(spec));
  spec.chunks[29].resize(10);
  const std::string truncated = dir_.write("truncated.laz", buildLaz(spec));
  const ReadOutcome sequential = readAll(truncated, 1, 7);
  EXPECT_EQ(sequential.records.size(), 28 * expected[0].size());  // 4 batches of 7
  EXPECT_NE(sequential.error.find("truncated or corrupt LAZ data: chunk 30 of 40"), std::string::npos)
      << sequential.error;

  // Arenas of 1 thread (the reader decodes every chunk itself), 2, and more threads than cores.
  for (const int threads : {1, 2, 5}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      for (const std::size_t in_flight : {std::size_t{2}, std::size_t{7}}) {
        for (const std::size_t batch : {std::size_t{1}, std::size_t{7}, std::size_t{1000}}) {
          SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(in_flight) +
                       " chunks in flight, batch " + std::to_string(batch));
          const ReadOutcome read = readAll(whole, in_flight, batch);
          EXPECT_EQ(read.error, "");
          EXPECT_EQ(read.records, concatenated(expected));
          const ReadOutcome stopped = readAll(truncated, in_flight, batch);
          EXPECT_EQ(stopped.error, sequential.error);
          // Batches of 7 stop on the call that asks for record 30: the 28 before it were handed.
          const std::size_t handed = batch == 1 ? 29 : batch == 7 ? 28 : 0;
          EXPECT_EQ(stopped.records.size(), handed * expected[0].size());
        }
      }
    });
  }
}

TEST_F(LazReader, ReadsVariableChunksATableAtTheEndAndNoTable) {
  std::vector<std::string> expected;
  LazSpec spec;
  for (int i = 0; i < 3; ++i) {
    expected.push_back(record(3, 0, i));
    spec.chunks.push_back(onePointChunk(expected.back()));
  }
  spec.chunk_size = 0xFFFFFFFFu;
  spec.chunk_points = {1, 1, 1};
  EXPECT_EQ(records(buildLaz(spec)), concatenated(expected));
  spec.table = Table::kAtTheEnd;
  EXPECT_EQ(records(buildLaz(spec)), concatenated(expected));
  spec.chunk_size = 1;
  spec.table = Table::kMissing;  // fixed chunks follow one another
  EXPECT_EQ(records(buildLaz(spec)), concatenated(expected));
  // A chunk table listing more chunks than the header's points: the rest is not read.
  spec.table = Table::kAfterChunks;
  spec.points = 2;
  EXPECT_EQ(records(buildLaz(spec)), concatenated({expected[0], expected[1]}));
}

TEST_F(LazReader, RefusesMalformedVlrsNamingTheField) {
  LazSpec base;
  base.chunks = {onePointChunk(record(3, 0, 0))};
  constexpr std::size_t kPayloadAt = 227 + 54;
  struct Case {
    const char* what;
    LazSpec spec;
    std::size_t at;
    const char* message;
  };
  std::vector<Case> cases;
  auto add = [&](const char* what, auto edit, std::size_t at, const char* message) {
    LazSpec spec = base;
    edit(spec);
    cases.push_back({what, spec, at, message});
  };
  add(
      "coder", [](LazSpec& s) { s.coder = 1; }, kPayloadAt + 2, "names coder 1");
  add(
      "compressor", [](LazSpec& s) { s.compressor = 4; }, kPayloadAt, "names compressor 4");
  add(
      "layered", [](LazSpec& s) { s.compressor = 3; }, kPayloadAt + 34,
      "is POINT10, an item of the point-wise coder, which the layered coder (compressor 3) does not code");
  add(
      "no items", [](LazSpec& s) { s.items = std::vector<Item>{}; }, kPayloadAt, "the laszip VLR has 34 bytes");
  add(
      "item count", [](LazSpec& s) { s.vlr_bytes = 34 + 6 * 2; }, kPayloadAt + 32, "declares 3 items but holds 2");
  add(
      "POINT14",
      [](LazSpec& s) {
        s.items = std::vector<Item>{{10, 30, 2}, {kGpsTime11, 4, 2}};
      },
      kPayloadAt + 34, "is POINT14, an item of LAS 1.4 point formats 6 to 10");
  add(
      "version 3", [](LazSpec& s) { s.items = itemsOf(3, 0, 3); }, kPayloadAt + 34 + 4, "POINT10 version 3");
  add(
      "version 0", [](LazSpec& s) { s.items = itemsOf(3, 0, 0); }, kPayloadAt + 34 + 4, "POINT10 version 0");
  add(
      "size",
      [](LazSpec& s) {
        s.items = std::vector<Item>{{kPoint10, 20, 2}, {kGpsTime11, 8, 2}, {kRgb12, 8, 2}};
      },
      kPayloadAt + 34 + 12 + 2, "RGB12 of 8 bytes");
  add(
      "order",
      [](LazSpec& s) {
        s.items = std::vector<Item>{{kPoint10, 20, 2}, {kRgb12, 6, 2}, {kGpsTime11, 8, 2}};
      },
      kPayloadAt + 34, "are not the records of point format 3 with 34 bytes");
  add(
      "extra bytes",
      [](LazSpec& s) {
        s.extra = 5;
        s.items = itemsOf(3, 4, 2);
        s.chunks = {onePointChunk(record(3, 5, 0))};
      },
      kPayloadAt + 34, "BYTE (4 bytes)) are not the records of point format 3 with 39 bytes");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string message = error(buildLaz(c.spec));
    EXPECT_NE(message.find("cloud.laz' at byte " + std::to_string(c.at) + ":"), std::string::npos) << message;
    EXPECT_NE(message.find(c.message), std::string::npos) << message;
  }

  // The format byte's compression bits without the VLR (its user id changed to "Xaszip encoded").
  std::string file = buildLaz(base);
  file[227 + 2] = 'X';
  const std::string message = error(file);
  EXPECT_NE(message.find("at byte 104"), std::string::npos) << message;
  EXPECT_NE(message.find("no laszip VLR"), std::string::npos) << message;
}

TEST_F(LazReader, RefusesPointFormatsBeyondThree) {
  // Point format 6 (30-byte records) written as POINT10 and 10 extra bytes.
  LazSpec spec;
  spec.format = 0;
  spec.extra = 10;
  spec.chunks = {onePointChunk(record(0, 10, 0))};
  std::string file = buildLaz(spec);
  file[104] = static_cast<char>(0x86);
  const std::string message = error(file);
  EXPECT_NE(message.find("point format 6 compressed with the point-wise LAZ coder"), std::string::npos) << message;
}

TEST_F(LazReader, RefusesMalformedChunkTables) {
  LazSpec base;
  for (int i = 0; i < 3; ++i) base.chunks.push_back(onePointChunk(record(3, 0, i)));
  const std::size_t point_offset = 227 + 54 + 34 + 18;
  const std::size_t table_at = point_offset + 8 + 3 * (34 + 4);
  {
    LazSpec spec = base;
    spec.table_version = 1;
    const std::string message = error(buildLaz(spec));
    EXPECT_NE(message.find("at byte " + std::to_string(table_at) + ": chunk table version 1"), std::string::npos)
        << message;
  }
  {
    LazSpec spec = base;
    spec.table_chunks = 2;  // 2 chunks of one point for 3 points
    const std::string message = error(buildLaz(spec));
    EXPECT_NE(message.find("chunks hold 2 points, where the header declares 3"), std::string::npos) << message;
  }
  {
    LazSpec spec = base;
    spec.table_chunks = 4;  // more chunks than the bytes before the table can hold
    const std::string message = error(buildLaz(spec));
    EXPECT_NE(message.find("lists 4 chunks, but the 114 bytes of compressed points hold at most 3"), std::string::npos)
        << message;
  }
  {
    LazSpec spec = base;
    spec.chunk_size = 0xFFFFFFFFu;
    spec.table = Table::kMissing;
    const std::string message = error(buildLaz(spec));
    EXPECT_NE(message.find("at byte " + std::to_string(point_offset) + ": the chunk table was never written"),
              std::string::npos)
        << message;
  }
  {
    std::string file = buildLaz(base);
    put<std::int64_t>(file, point_offset, -5);
    const std::string message = error(file);
    EXPECT_NE(message.find("the chunk table's offset -5 points outside the compressed points"), std::string::npos)
        << message;
  }
  {
    // The table cut short: its entries run past the end of the file.
    const std::string file = buildLaz(base);
    const std::string message = error(file.substr(0, table_at + 9));
    EXPECT_NE(message.find("truncated or corrupt LAZ data: the chunk table"), std::string::npos) << message;
  }
}

TEST_F(LazReader, ATruncatedChunkStopsAtTheEndOfTheFile) {
  LazSpec spec;
  for (int i = 0; i < 3; ++i) spec.chunks.push_back(onePointChunk(record(1, 0, i)));
  spec.format = 1;
  spec.table = Table::kMissing;
  const std::string file = buildLaz(spec);
  const std::size_t cut = file.size() - 20;  // inside the third point's raw record
  const std::string message = error(file.substr(0, cut));
  EXPECT_NE(message.find("at byte " + std::to_string(cut) + ": truncated or corrupt LAZ data: chunk 3"),
            std::string::npos)
      << message;
}

TEST_F(LazReader, GarbageEndsInAnErrorOrInPointsNeverInACrash) {
  // Random bytes for the compressed points of every item and version: the decoders must stay
  // inside their models and the chunk (this runs under ASan and UBSan too).
  std::mt19937 random(42);
  int errors = 0, trials = 0;
  for (const std::uint16_t version : {std::uint16_t{1}, std::uint16_t{2}}) {
    for (unsigned format = 0; format <= 3; ++format) {
      for (const std::uint16_t compressor : {std::uint16_t{1}, std::uint16_t{2}}) {
        for (int seed = 0; seed < 4; ++seed) {
          LazSpec spec;
          spec.format = format;
          spec.extra = 3;
          spec.compressor = compressor;
          spec.chunk_size = 50'000;
          spec.table = Table::kMissing;
          spec.items = itemsOf(format, 3, version);
          std::string garbage = record(format, 3, seed);
          for (int i = 0; i < 600; ++i) garbage += static_cast<char>(random());
          spec.chunks = {garbage};
          spec.points = 2'000;
          ++trials;
          try {
            records(buildLaz(spec));
          } catch (const Error& e) {
            ++errors;
            EXPECT_NE(std::string(e.what()).find("truncated or corrupt LAZ data"), std::string::npos) << e.what();
          }
        }
      }
    }
  }
  // Garbage mostly runs out before 2000 points; models that adapt to what garbage decodes to can
  // also make it last.
  EXPECT_GT(errors, 0);
  std::cout << "garbage: " << errors << " of " << trials << " streams ran out of bytes\n";
}

}  // namespace
}  // namespace plumb::io
