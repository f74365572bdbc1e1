#pragma once
// The LAS and LAZ reader (las_reader.cpp) beyond PointReader: the point records themselves, as
// the file stores them (LAZ: decompressed to the same bytes), for callers that need fields Plumb
// does not keep (GPS time, classification, extra bytes) and for tests that compare LAZ with LAS.
//
// Not thread-safe: one thread reads one reader (which may decode LAZ chunks on oneTBB's workers).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/io/point_reader.h"

namespace plumb::io {

class LasPointReader : public PointReader {
 public:
  // Bytes per record: the header's record length (the point format's fields, then extra bytes).
  virtual std::size_t recordLength() const = 0;

  // Replaces `records` with the next records, at most `max_records` (>= 1), each recordLength()
  // bytes in the LAS layout; returns how many, 0 when the file is exhausted. Throws plumb::Error
  // like read(). Shares read()'s position: each record is handed out once, by one or the other.
  virtual std::size_t readRecords(std::vector<std::byte>& records, std::size_t max_records) = 0;

 protected:
  using PointReader::PointReader;
};

struct LasReadOptions {
  // LAZ with a chunk table of two or more chunks: how many chunks are decoded ahead at once, as
  // oneTBB tasks of the calling thread's arena (laz_chunk_window.h); 0: twice the arena's threads
  // for files of 2^16 points or more, else none; 1: none, the reading thread decodes as it reads.
  // The records, and the errors, are the same either way.
  std::size_t laz_chunks_in_flight = 0;
};

// Opens a LAS or LAZ file (throws plumb::Error as openLas does).
std::unique_ptr<LasPointReader> openLasRecords(const std::string& path, const LasReadOptions& options = {});

}  // namespace plumb::io
