// Comparing result vectors in the tests.
#pragma once

#include <cmath>
#include <vector>

namespace snh::test {

// |a - b| / |b| (2-norms): a's relative difference from the reference b.
inline double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, n = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    d += (a[i] - b[i]) * (a[i] - b[i]);
    n += b[i] * b[i];
  }
  return std::sqrt(d / n);
}

}  // namespace snh::test
