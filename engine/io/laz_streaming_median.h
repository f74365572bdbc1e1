#pragma once
// The streaming median of five that LASzip's POINT10 v2 and POINT14 v3/v4 coders predict x and y
// differences with, after the LASzip reference implementation, src/laszip_common_v2.hpp (read,
// not copied). Shared by laz_items_v2.cpp and laz_items_v3.cpp.

#include <array>
#include <cstddef>
#include <cstdint>

namespace plumb::io {

// The median of the last five values added, kept sorted. Each new value replaces the largest or
// the smallest of the five, alternately by where values fall: after a value in the upper half the
// smallest goes next, after one in the lower half the largest, so the five stay around the median.
class StreamingMedian5 {
 public:
  void reset() {
    values_ = {};
    replace_largest_ = true;
  }

  std::int32_t median() const { return values_[2]; }

  void add(std::int32_t value) {
    if (replace_largest_) {
      const bool upper = value >= values_[2];
      std::size_t i = 4;
      for (; i > 0 && values_[i - 1] > value; --i) values_[i] = values_[i - 1];
      values_[i] = value;
      if (upper) replace_largest_ = false;
    } else {
      const bool lower = value <= values_[2];
      std::size_t i = 0;
      for (; i < 4 && values_[i + 1] < value; ++i) values_[i] = values_[i + 1];
      values_[i] = value;
      if (lower) replace_largest_ = true;
    }
  }

 private:
  std::array<std::int32_t, 5> values_{};
  bool replace_largest_ = true;
};

}  // namespace plumb::io
