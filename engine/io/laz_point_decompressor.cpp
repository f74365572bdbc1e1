#include "engine/io/laz_point_decompressor.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>

#include "engine/io/byte_order.h"

namespace plumb::io {

LazPointDecompressor::LazPointDecompressor(FileSource& source, const LaszipVlr& vlr, std::uint64_t point_offset,
                                           std::uint64_t data_end, std::size_t record_length, std::uint64_t point_count)
    : source_(source),
      input_(source),
      decoder_(input_),
      chunked_(vlr.compressor == LazCompressor::kPointwiseChunked || vlr.compressor == LazCompressor::kLayeredChunked),
      chunk_size_(vlr.chunk_size),
      point_offset_(point_offset),
      data_end_(std::min(data_end, source.size())),
      record_length_(record_length),
      point_count_(point_count),
      layered_(vlr.compressor == LazCompressor::kLayeredChunked) {
  assert((vlr.compressor == LazCompressor::kPointwise || chunked_) && "readLaszipVlr refuses compressor 0 here");
  makeItems(vlr);
  if (chunked_) {
    table_ = readLazChunkTable(source_, point_offset_, chunk_size_, record_length_, point_count_);
  } else {
    table_.chunks_start = point_offset_;
  }
}

LazPointDecompressor::LazPointDecompressor(FileSource& source, const LaszipVlr& vlr, LazChunkTable table,
                                           std::size_t record_length, std::size_t first_number, std::size_t file_chunks)
    : source_(source),
      input_(source),
      decoder_(input_),
      chunked_(true),
      chunk_size_(vlr.chunk_size),
      point_offset_(table.chunks_start),
      data_end_(source.size()),
      record_length_(record_length),
      point_count_(0),
      layered_(vlr.compressor == LazCompressor::kLayeredChunked),
      table_(std::move(table)),
      first_number_(first_number),
      file_chunks_(file_chunks) {
  assert((vlr.compressor == LazCompressor::kPointwiseChunked || layered_) && "chunks are read from chunked LAZ only");
  assert(table_.present && "pass the chunks to decode");
  makeItems(vlr);
  for (const LazChunk& chunk : table_.chunks) {
    assert(chunk.points > 0 && chunk.offset + chunk.bytes <= source.size() && "chunks lie inside the file");
    point_count_ += chunk.points;
  }
}

void LazPointDecompressor::makeItems(const LaszipVlr& vlr) {
  std::size_t offset = 0;
  for (const LazItem& item : vlr.items) {
    if (layered_) {
      layered_items_.push_back(makeLazLayeredItemDecoder(item));
      assert(layered_items_.back() && "readLaszipVlr checks that every item has a decoder");
      first_layer_.push_back(layers_.size());
      for (std::size_t l = 0; l < layered_items_.back()->layerCount(); ++l) {
        layers_.push_back(std::make_unique<LazLayer>(source_));
        layer_pointers_.push_back(layers_.back().get());
      }
    } else {
      items_.push_back(makeLazItemDecoder(item));
      assert(items_.back() && "readLaszipVlr checks that every item has a decoder");
    }
    item_offsets_.push_back(offset);
    offset += item.size;
  }
  first_layer_.push_back(layers_.size());
  assert(offset == record_length_ && "readLaszipVlr checks that the items make the record");
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
                 "chunk " + std::to_string(first_number_ + chunk_ + 1) + " of " +
                     std::to_string(file_chunks_ != 0 ? file_chunks_ : table_.chunks.size()) + " (" +
                     std::to_string(chunk.points) + " points in " + std::to_string(chunk.bytes) + " bytes from byte " +
                     std::to_string(chunk.offset) + ")");
    left_in_chunk_ = chunk.points;
  } else {
    // No table: this chunk starts where the previous one's compressed data ended.
    const std::uint64_t begin = chunk_ == 0 ? table_.chunks_start : (layered_ ? next_chunk_ : input_.offset());
    input_.reset(begin, std::max(begin, data_end_),
                 "chunk " + std::to_string(chunk_ + 1) + " (from byte " + std::to_string(begin) +
                     "; the file has no chunk table)");
    left_in_chunk_ = std::min<std::uint64_t>(chunk_size_, remaining);
  }
  ++chunk_;
  // The first point is stored raw; it starts every item's models.
  input_.read(std::span(record, record_length_));
  if (layered_) {
    startLayers(input_.end());
    for (std::size_t i = 0; i < layered_items_.size(); ++i) {
      const std::span<LazLayer* const> layers(layer_pointers_.data() + first_layer_[i],
                                              first_layer_[i + 1] - first_layer_[i]);
      layered_items_[i]->start(record + item_offsets_[i], layers, context_);
    }
    return;
  }
  for (std::size_t i = 0; i < items_.size(); ++i) items_[i]->start(record + item_offsets_[i]);
  decoder_.start();
}

void LazPointDecompressor::startLayers(std::uint64_t chunk_end) {
  std::array<std::byte, 4> word{};
  const std::uint64_t count_at = input_.offset();
  input_.read(word);
  const auto count = loadLittleEndian<std::uint32_t>(word.data());
  if (count < left_in_chunk_) {
    throw source_.errorAt(count_at, input_.what() + " says it holds " + std::to_string(count) + " points, where " +
                                        std::to_string(left_in_chunk_) + " are read from it: a corrupt LAZ file");
  }
  const std::uint64_t sizes_at = input_.offset();
  for (const std::unique_ptr<LazLayer>& layer : layers_) {
    input_.read(word);
    layer->bytes = loadLittleEndian<std::uint32_t>(word.data());
  }
  std::uint64_t at = input_.offset();
  std::size_t item = 0;
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    while (l >= first_layer_[item + 1]) ++item;
    LazLayer& layer = *layers_[l];
    const std::string name = "layer " + layered_items_[item]->layerName(l - first_layer_[item]);
    if (layer.bytes > chunk_end - at) {
      throw source_.errorAt(sizes_at + 4 * l, name + " of " + input_.what() + " has " + std::to_string(layer.bytes) +
                                                  " bytes from byte " + std::to_string(at) +
                                                  ", past the chunk's end at byte " + std::to_string(chunk_end) +
                                                  ": a corrupt or truncated LAZ file");
    }
    if (l == 0 && layer.bytes == 0 && left_in_chunk_ > 1) {
      throw source_.errorAt(sizes_at, name + " of " + input_.what() + " is empty, but the chunk has " +
                                          std::to_string(left_in_chunk_) +
                                          " points, whose coordinates it codes: a corrupt LAZ file");
    }
    layer.input.reset(at, at + layer.bytes, name + " of " + input_.what());
    if (layer.bytes != 0 && left_in_chunk_ > 1) layer.decoder.start();
    at += layer.bytes;
  }
  next_chunk_ = at;
}

void LazPointDecompressor::decode(std::span<std::byte> records) {
  const std::size_t count = records.size() / record_length_;
  assert(count <= point_count_ - decoded_ && "decode() past the declared points");
  for (std::size_t r = 0; r < count; ++r) {
    std::byte* record = records.data() + r * record_length_;
    if (left_in_chunk_ == 0) {
      startChunk(record);
    } else if (layered_) {
      // The context starts at 0 for every point: POINT14 v3 sets it only when the channel switches.
      unsigned context = 0;
      for (std::size_t i = 0; i < layered_items_.size(); ++i)
        layered_items_[i]->decode(record + item_offsets_[i], context);
    } else {
      for (std::size_t i = 0; i < items_.size(); ++i) items_[i]->decode(decoder_, record + item_offsets_[i]);
    }
    --left_in_chunk_;
    ++decoded_;
  }
}

}  // namespace plumb::io
