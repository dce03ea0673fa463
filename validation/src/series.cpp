// The validation's time series (docs/validation.md#method).
#include "cvtplant/validation/series.hpp"

#include <algorithm>
#include <cmath>

namespace cvt::validation {

void Series::reserve(std::size_t n) {
  for (const auto c : kSeriesColumns) (this->*c).reserve(n);
}

Series Series::select(std::size_t n, std::size_t step) const {
  Series o;
  for (const auto c : kSeriesColumns) {
    const std::vector<double>& from = this->*c;
    std::vector<double>& to = o.*c;
    for (std::size_t i = 0; i < std::min(n, from.size()); i += std::max<std::size_t>(1, step)) to.push_back(from[i]);
  }
  return o;
}

double whole_wrap_slip(double lo, double hi) {
  if (!(lo <= hi)) return std::nan("");  // no part in the wrap (NaN)
  if (lo > 0.0) return lo;
  if (hi < 0.0) return hi;
  return 0.0;
}

}  // namespace cvt::validation
