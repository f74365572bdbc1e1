#pragma once
// LASzip's integer corrector coding, decoder side, after the LASzip reference implementation,
// src/integercompressor.cpp (read, not copied); Isenburg 2013, "LASzip: lossless compression of
// LiDAR data", PE&RS 79(2), which describes predicting each field and coding the correction.
//
// A value is coded as a prediction (the caller's) plus a corrector c, folded into the field's
// range of 2^bits values:
//   1. k, the number of bits of c, with an adaptive symbol model chosen by the caller's context:
//      c lies in [-(2^k - 1), -2^(k-1)] or [2^(k-1) + 1, 2^k] (k = 0: c is 0 or 1).
//   2. k = 0: c with an adaptive bit model. 0 < k <= bits_high (8): c's offset in its interval
//      with an adaptive symbol model of 2^k symbols, one model per k. k > bits_high: the top
//      bits_high bits with that model, the k - bits_high low bits raw. k = 32: c is -2^31.
//   3. The value is prediction + c, folded back into [0, 2^bits) (for bits 1 to 31).
// k of the last value is exposed: the item coders choose the next field's context from it.

#include <cstdint>

#include "engine/io/laz_arithmetic_decoder.h"

namespace plumb::io {

class LazIntegerDecompressor {
 public:
  // `bits`: the field's width, 1 to 32 (32 for any full 32-bit difference). `contexts`: how many
  // models step 1 chooses from (>= 1). `bits_high`: the corrector bits coded with a model.
  LazIntegerDecompressor(unsigned bits, unsigned contexts, unsigned bits_high = 8);

  // Back to the initial models, as at the start of every chunk.
  void reset();

  // The next value: `prediction` plus the decoded corrector, folded. `context` < contexts.
  std::int32_t decompress(LazArithmeticDecoder& decoder, std::int32_t prediction, unsigned context);

  // k of the last decompress() (0 to 32).
  unsigned k() const { return k_; }

 private:
  std::uint32_t readCorrector(LazArithmeticDecoder& decoder, unsigned context);

  unsigned bits_high_;
  unsigned corrector_bits_;        // the largest k
  std::uint32_t corrector_range_;  // 2^bits, or 0 for 32 bits (no folding)
  std::int32_t corrector_min_;     // c for k = 32
  LazModelSet k_models_;           // per context
  LazBitModel k0_model_;
  LazModelSet corrector_models_;  // [k - 1] for k = 1 .. corrector_bits_
  unsigned k_ = 0;
};

}  // namespace plumb::io
