#pragma once
// The chunk table of a point-wise chunked LAZ file (compressor 2), after the LASzip reference
// implementation, src/lasreadpoint.cpp (read_chunk_table; read, not copied).
//
// The point data starts with an i64: the file offset of the chunk table (-1: stored in the
// file's last 8 bytes instead, by a writer that could not seek back; the offset of the i64
// itself: never written, the writer was interrupted). The chunks follow it back to back. The
// table: u32 version (0), u32 chunk count, then per chunk, arithmetic-coded with one
// LazIntegerDecompressor of 32 bits and 2 contexts, each value predicted by the previous chunk's:
// for variable chunks (chunk size 0xFFFFFFFF, or 0) its point count (context 0), then for every
// chunk its size in bytes (context 1).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/io/file_source.h"

namespace plumb::io {

struct LazChunk {
  std::uint64_t offset = 0;  // file offset of its first byte (the first point, stored raw)
  std::uint64_t bytes = 0;
  std::uint64_t points = 0;
};

struct LazChunkTable {
  std::uint64_t chunks_start = 0;  // file offset of the first chunk
  // False: no table (an interrupted writer, fixed chunk sizes only); the chunks are then read one
  // after another, each starting where the previous one's compressed data ended.
  bool present = false;
  std::vector<LazChunk> chunks;  // those that hold the file's points, in order; none empty
};

// Reads the chunk table of the point data at `point_offset` for `point_count` points of
// `record_length` bytes in chunks of `chunk_size` points (0xFFFFFFFF or 0: variable). Throws
// plumb::Error naming the file and the offset when the table's offset lies outside the file or
// before the chunks, its version is not 0, it lists more chunks than the bytes before it can hold
// or too few points, or a chunk runs past the table. With no points, no table is read.
LazChunkTable readLazChunkTable(FileSource& source, std::uint64_t point_offset, std::uint32_t chunk_size,
                                std::size_t record_length, std::uint64_t point_count);

}  // namespace plumb::io
