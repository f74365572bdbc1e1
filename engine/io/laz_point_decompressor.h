#pragma once
// The point data of a LAZ file written with the point-wise LASzip coder (compressor 1, one
// stream; compressor 2, chunks) or the layered one (compressor 3, chunks of layers), decoded into the exact bytes of
// the uncompressed LAS point records, after the LASzip reference implementation, src/lasreadpoint.cpp (read, not
// copied); Isenburg 2013, "LASzip: lossless compression of LiDAR data", PE&RS 79(2).
//
//   1. Compressor 2: read the chunk table (laz_chunk_table.h). Compressor 1: the points form one
//      chunk that starts at the point data.
//   2. Each chunk: its first point stored raw (every item's bytes, the record as it is), which
//      starts every item decoder (laz_items.h); then the arithmetic-coded stream of the others,
//      each item decoding its bytes of the record in turn.
//   3. A chunk's compressed bytes end where the table says (or at the end of the point data):
//      a decoder that needs more stops with plumb::Error naming the chunk and the offset.
//   4. Layered chunks (compressor 3): the first point raw, a u32 count of the chunk's points,
//      then a u32 size per layer of every item in turn (laz_layered_items.h), then the layers back
//      to back, each decoded by its own arithmetic decoder over its own bytes. A layer that runs
//      past the chunk stops with plumb::Error naming the layer, the chunk and the offset.
//
// Streaming: one chunk's models and a 64 KiB read buffer, never the whole file. Not thread-safe.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "engine/io/file_source.h"
#include "engine/io/laszip_vlr.h"
#include "engine/io/laz_arithmetic_decoder.h"
#include "engine/io/laz_chunk_table.h"
#include "engine/io/laz_items.h"
#include "engine/io/laz_layered_items.h"

namespace plumb::io {

class LazPointDecompressor {
 public:
  // `vlr`: checked by readLaszipVlr, compressor 1, 2 or 3. The point data starts at `point_offset`
  // and ends by `data_end` (the EVLRs or the end of the file); `point_count` records of
  // `record_length` bytes. Reads the chunk table; throws plumb::Error when it is malformed.
  LazPointDecompressor(FileSource& source, const LaszipVlr& vlr, std::uint64_t point_offset, std::uint64_t data_end,
                       std::size_t record_length, std::uint64_t point_count);

  // Decodes only the chunks of `table` (present, its chunks in any order, none empty), for a
  // reader that finds chunks itself: a COPC node is one chunk, located by the octree's hierarchy
  // rather than by the chunk table; or one chunk of a file decoded in parallel (laz_chunk_window.h).
  // `vlr`: checked by readLaszipVlr, compressor 2 or 3. Errors call chunk i of `table` "chunk
  // first_number + i + 1 of file_chunks" (file_chunks 0: of table.chunks.size()), as the reader of
  // the whole file would.
  LazPointDecompressor(FileSource& source, const LaszipVlr& vlr, LazChunkTable table, std::size_t record_length,
                       std::size_t first_number = 0, std::size_t file_chunks = 0);

  // Decodes the next records.size() / record_length records (no more than remain) into
  // `records`. Throws plumb::Error on truncated or corrupt compressed data.
  void decode(std::span<std::byte> records);

  // Records decoded whole so far; after decode() threw, those before the one that failed.
  std::uint64_t decoded() const { return decoded_; }

  // The chunk table read by the first constructor (present false: none, or compressor 1).
  const LazChunkTable& table() const { return table_; }

 private:
  void makeItems(const LaszipVlr& vlr);
  void startChunk(std::byte* record);
  void startLayers(std::uint64_t chunk_end);

  FileSource& source_;
  LazByteInput input_;
  LazArithmeticDecoder decoder_;
  std::vector<std::unique_ptr<LazItemDecoder>> items_;
  std::vector<std::size_t> item_offsets_;  // in the record
  // Layered coder only: its items, every item's layers in turn, and each item's first layer.
  std::vector<std::unique_ptr<LazLayeredItemDecoder>> layered_items_;
  std::vector<std::unique_ptr<LazLayer>> layers_;
  std::vector<LazLayer*> layer_pointers_;
  std::vector<std::size_t> first_layer_;
  unsigned context_ = 0;          // the scanner channel of a chunk's first point
  std::uint64_t next_chunk_ = 0;  // layered chunks without a table: where the next one starts
  bool chunked_;
  std::uint32_t chunk_size_;
  std::uint64_t point_offset_, data_end_;
  std::size_t record_length_;
  std::uint64_t point_count_;
  bool layered_;
  LazChunkTable table_;
  std::size_t chunk_ = 0;         // chunks started
  std::size_t first_number_ = 0;  // how errors number the chunks of table_
  std::size_t file_chunks_ = 0;
  std::uint64_t left_in_chunk_ = 0;  // points of the current chunk still to decode
  std::uint64_t decoded_ = 0;
};

}  // namespace plumb::io
