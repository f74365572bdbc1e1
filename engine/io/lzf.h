#pragma once
// LZF decompression (Marc Lehmann's liblzf format), as PCL's "binary_compressed" PCD files use it.
//
// The stream is a sequence of chunks, each opened by a control byte c:
//   c < 32   a literal run: the next c + 1 input bytes are copied to the output;
//   c >= 32  a back reference: length (c >> 5) + 2, plus the next input byte when c >> 5 == 7;
//            then one more byte b, and the bytes are copied from ((c & 0x1f) << 8) + b + 1
//            bytes back from the current output position (source and destination may overlap,
//            which repeats a short pattern).

#include <cstddef>
#include <span>

namespace plumb::io {

// Decompresses all of `in` into `out`. Returns true when every chunk decoded and fit in `out`;
// `written` is then the number of output bytes (it may be less than out.size(): the caller
// compares it with the size it expects). Returns false on malformed input: a chunk cut short by
// the end of `in`, a back reference before the start of the output, or more output than
// out.size(); `written` then says how many bytes were decoded before the fault. Never reads or
// writes outside the two spans, whatever `in` holds. Thread-safe (no state).
bool lzfDecompress(std::span<const std::byte> in, std::span<std::byte> out, std::size_t& written);

}  // namespace plumb::io
