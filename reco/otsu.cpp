#include "reco/otsu.h"

#include <cassert>

namespace plumb::reco {

std::size_t otsuHighClassSize(std::span<const double> descending, double separation) {
  const std::size_t n = descending.size();
  if (n < 2) return n;
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    assert((i == 0 || descending[i] <= descending[i - 1]) && "otsuHighClassSize takes values sorted descending");
    total += descending[i];
  }
  std::size_t best_split = n;
  double best_variance = 0.0;
  double high_sum = 0.0;
  for (std::size_t k = 1; k < n; ++k) {  // the first k values are the high class
    high_sum += descending[k - 1];
    const double w_high = static_cast<double>(k) / static_cast<double>(n);
    const double w_low = 1.0 - w_high;
    const double mean_high = high_sum / static_cast<double>(k);
    const double mean_low = (total - high_sum) / static_cast<double>(n - k);
    const double between = w_high * w_low * (mean_high - mean_low) * (mean_high - mean_low);
    if (between > best_variance) {
      best_variance = between;
      best_split = k;
    }
  }
  if (best_split == n) return n;  // all equal
  return descending[best_split] < separation * descending[best_split - 1] ? best_split : n;
}

}  // namespace plumb::reco
