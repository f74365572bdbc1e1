#include "engine/io/laz_chunk_table.h"

#include <algorithm>
#include <array>

#include "engine/io/byte_order.h"
#include "engine/io/laz_arithmetic_decoder.h"
#include "engine/io/laz_integer_decompressor.h"

namespace plumb::io {
namespace {

constexpr std::uint64_t kTableOffsetBytes = 8;
constexpr std::uint64_t kTableHeaderBytes = 8;  // version, chunk count
constexpr std::int64_t kTableAtFileEnd = -1;

std::uint64_t readU64At(FileSource& source, std::uint64_t at, const char* what) {
  std::array<std::byte, 8> bytes{};
  source.seek(at);
  source.readExactly(bytes, what);
  return loadLittleEndian<std::uint64_t>(bytes.data());
}

}  // namespace

LazChunkTable readLazChunkTable(FileSource& source, std::uint64_t point_offset, std::uint32_t chunk_size,
                                std::size_t record_length, std::uint64_t point_count) {
  LazChunkTable table;
  table.chunks_start = point_offset + kTableOffsetBytes;
  if (point_count == 0) return table;  // nothing to decode (a writer may leave the table out)
  const bool variable = chunk_size == 0 || chunk_size == 0xFFFFFFFFu;

  auto table_offset = static_cast<std::int64_t>(readU64At(source, point_offset, "the chunk table's offset"));
  if (table_offset == kTableAtFileEnd || table_offset == 0) {
    // A writer to a stream that could not seek put the offset at the end (LASzip 2.x: also 0).
    if (source.size() < table.chunks_start + kTableOffsetBytes) {
      throw source.errorAt(point_offset,
                           "the chunk table's offset is stored at the end of the file, "
                           "which is too short to hold it: a truncated LAZ file");
    }
    table_offset = static_cast<std::int64_t>(
        readU64At(source, source.size() - kTableOffsetBytes, "the chunk table's offset at the end of the file"));
  }
  if (static_cast<std::uint64_t>(table_offset) == point_offset) {
    if (variable) {
      throw source.errorAt(point_offset,
                           "the chunk table was never written (the writer was interrupted) and the "
                           "chunks have variable point counts, which only the table gives");
    }
    return table;  // fixed chunks: read one after another
  }
  if (table_offset < 0 || static_cast<std::uint64_t>(table_offset) < table.chunks_start ||
      static_cast<std::uint64_t>(table_offset) + kTableHeaderBytes > source.size()) {
    throw source.errorAt(point_offset, "the chunk table's offset " + std::to_string(table_offset) +
                                           " points outside the compressed points (bytes " +
                                           std::to_string(table.chunks_start) + " to " + std::to_string(source.size()) +
                                           "): a truncated or corrupt LAZ file");
  }
  const auto table_at = static_cast<std::uint64_t>(table_offset);

  std::array<std::byte, kTableHeaderBytes> header{};
  source.seek(table_at);
  source.readExactly(header, "the chunk table's header");
  const auto version = loadLittleEndian<std::uint32_t>(header.data());
  const auto count = loadLittleEndian<std::uint32_t>(header.data() + 4);
  if (version != 0) {
    throw source.errorAt(table_at, "chunk table version " + std::to_string(version) +
                                       ", where LASzip writes 0: a corrupt or newer LAZ file");
  }
  // A chunk holds at least its first point raw.
  const std::uint64_t room = (table_at - table.chunks_start) / record_length;
  if (count > room) {
    throw source.errorAt(table_at + 4, "the chunk table lists " + std::to_string(count) + " chunks, but the " +
                                           std::to_string(table_at - table.chunks_start) +
                                           " bytes of compressed points hold at most " + std::to_string(room) +
                                           ": a corrupt LAZ file");
  }

  table.present = true;
  LazByteInput input(source);
  input.reset(table_at + kTableHeaderBytes, source.size(), "the chunk table");
  LazArithmeticDecoder decoder(input);
  LazIntegerDecompressor entries(32, 2);
  entries.reset();
  if (count > 0) decoder.start();
  std::int32_t last_points = 0, last_bytes = 0;  // the previous entries, as coded
  std::uint64_t offset = table.chunks_start;
  std::uint64_t covered = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    LazChunk chunk;
    chunk.offset = offset;
    if (variable) {
      last_points = entries.decompress(decoder, last_points, 0);
      chunk.points = static_cast<std::uint32_t>(last_points);
    } else {
      chunk.points = chunk_size;
    }
    last_bytes = entries.decompress(decoder, last_bytes, 1);
    chunk.bytes = static_cast<std::uint32_t>(last_bytes);
    offset += chunk.bytes;
    if (offset > table_at) {
      throw source.errorAt(table_at + kTableHeaderBytes,
                           "chunk " + std::to_string(i + 1) + " of " + std::to_string(count) + " (" +
                               std::to_string(chunk.bytes) + " bytes from byte " + std::to_string(chunk.offset) +
                               ") runs past the chunk table at byte " + std::to_string(table_at) +
                               ": a corrupt chunk table or a truncated LAZ file");
    }
    // Keep the chunks that hold the declared points (a writer may list more; LASzip ignores them).
    if (covered < point_count && chunk.points > 0) {
      chunk.points = std::min(chunk.points, point_count - covered);
      covered += chunk.points;
      table.chunks.push_back(chunk);
    }
  }
  if (covered < point_count) {
    throw source.errorAt(table_at + 4, "the chunk table's " + std::to_string(count) + " chunks hold " +
                                           std::to_string(covered) + " points, where the header declares " +
                                           std::to_string(point_count) + ": a truncated or corrupt LAZ file");
  }
  return table;
}

}  // namespace plumb::io
