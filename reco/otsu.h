#pragma once
// Otsu's threshold (Otsu 1979, "A threshold selection method from gray-level histograms") on a
// handful of values: the split into a low and a high class that maximises the between-class
// variance. The seed stage (paper section 3.4) uses it to drop unstable planes by inlier count.

#include <cstddef>
#include <span>

namespace plumb::reco {

// How many of `descending` (sorted from largest to smallest) belong to the high class. All of
// them when there are fewer than two values, when they are all equal, or when the split is not
// clear: the low class is dropped only if its largest value is below `separation` times the
// smallest value of the high class (Otsu alone always splits, even 10000, 9000, 8000).
std::size_t otsuHighClassSize(std::span<const double> descending, double separation = 0.2);

}  // namespace plumb::reco
