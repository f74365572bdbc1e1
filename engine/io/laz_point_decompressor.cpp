#include "engine/io/laz_point_decompressor.h"

#include <algorithm>
#include <cassert>

namespace plumb::io {

LazPointDecompressor::LazPointDecompressor(FileSource& source, const LaszipVlr& vlr, std::uint64_t point_offset,
                                           std::uint64_t data_end, std::size_t record_length, std::uint64_t point_count)
    : source_(source),
      input_(source),
      decoder_(input_),
      chunked_(vlr.compressor == LazCompressor::kPointwiseChunked),
      chunk_size_(vlr.chunk_size),
      point_offset_(point_offset),
      data_end_(std::min(data_end, source.size())),
      record_length_(record_length),
      point_count_(point_count) {
  assert((vlr.compressor == LazCompressor::kPointwise || chunked_) && "only the point-wise coder is decoded here");
  std::size_t offset = 0;
  for (const LazItem& item : vlr.items) {
    items_.push_back(makeLazItemDecoder(item));
    assert(items_.back() && "readLaszipVlr checks that every item has a decoder");
    item_offsets_.push_back(offset);
    offset += item.size;
  }
  assert(offset == record_length && "readLaszipVlr checks that the items make the record");
  if (chunked_) {
    table_ = readLazChunkTable(source_, point_offset_, chunk_size_, record_length_, point_count_);
  } else {
    table_.chunks_start = point_offset_;
  }
}

void LazPointDecompressor::startChunk(std::byte* record) {
  const std::uint64_t remaining = point_count_ - decoded_;
  if (!chunked_) {
    input_.reset(point_offset_, std::max(point_offset_, data_end_),
                 "the compressed points (one stream of " + std::to_string(point_count_) + " points from byte " +
                     std::to_string(point_offset_) + ")");
    left_in_chunk_ = remaining;
  } else if (table_.present) {
    assert(chunk_ < table_.chunks.size() && "the chunk table covers the declared points");
    const LazChunk& chunk = table_.chunks[chunk_];
    input_.reset(chunk.offset, chunk.offset + chunk.bytes,
                 "chunk " + std::to_string(chunk_ + 1) + " of " + std::to_string(table_.chunks.size()) + " (" +
                     std::to_string(chunk.points) + " points in " + std::to_string(chunk.bytes) + " bytes from byte " +
                     std::to_string(chunk.offset) + ")");
    left_in_chunk_ = chunk.points;
  } else {
    // No table: this chunk starts where the previous one's compressed data ended.
    const std::uint64_t begin = chunk_ == 0 ? table_.chunks_start : input_.offset();
    input_.reset(begin, std::max(begin, data_end_),
                 "chunk " + std::to_string(chunk_ + 1) + " (from byte " + std::to_string(begin) +
                     "; the file has no chunk table)");
    left_in_chunk_ = std::min<std::uint64_t>(chunk_size_, remaining);
  }
  ++chunk_;
  // The first point is stored raw; it starts every item's models.
  input_.read(std::span(record, record_length_));
  for (std::size_t i = 0; i < items_.size(); ++i) items_[i]->start(record + item_offsets_[i]);
  decoder_.start();
}

void LazPointDecompressor::decode(std::span<std::byte> records) {
  const std::size_t count = records.size() / record_length_;
  assert(count <= point_count_ - decoded_ && "decode() past the declared points");
  for (std::size_t r = 0; r < count; ++r) {
    std::byte* record = records.data() + r * record_length_;
    if (left_in_chunk_ == 0) {
      startChunk(record);
    } else {
      for (std::size_t i = 0; i < items_.size(); ++i) items_[i]->decode(decoder_, record + item_offsets_[i]);
    }
    --left_in_chunk_;
    ++decoded_;
  }
}

}  // namespace plumb::io
