// Distribution of latencies (jitter, round-trip times) as the SIL reports
// them: nearest-rank percentiles, never a mean (docs/sil.md#figures).
// Host-only (std::vector): used by the bridge's pacing loop and the harness.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace cvt::sil {

struct LatencySummary {
  std::size_t n = 0;
  std::int64_t p50_ns = 0, p99_ns = 0, p999_ns = 0, max_ns = 0;
};

// Nearest rank: the smallest sample with at least q of all samples <= it.
inline LatencySummary summarize_latencies(std::vector<std::int64_t> v) {
  LatencySummary s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto rank = [&](double q) {
    auto k = static_cast<std::size_t>(q * static_cast<double>(v.size()) + 0.999999999);
    if (k < 1) k = 1;
    if (k > v.size()) k = v.size();
    return v[k - 1];
  };
  s.p50_ns = rank(0.50);
  s.p99_ns = rank(0.99);
  s.p999_ns = rank(0.999);
  s.max_ns = v.back();
  return s;
}

}  // namespace cvt::sil
