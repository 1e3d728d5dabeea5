#pragma once
// The order statistics the benchmarks print: the nearest rank on a sorted copy, 0 without samples.
#include <algorithm>
#include <vector>

namespace shadelab::bench {

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size() - 1) + 0.5))];
}

inline double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }

}  // namespace shadelab::bench
