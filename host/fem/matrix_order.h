// The two orders of a 3x3 matrix: the public API stores every matrix
// row-major (m[3 * row + col], like NumPy's C order and VTK), while the
// element math and the kernels use the column-major vec(F) of the paper
// (m[3 * col + row]). The conversions sit where the public structs are filled
// or read.
#pragma once

#include <array>
#include <cstddef>

namespace snh::fem {

// The flat index, in the other order, of flat index i of a 3x3: row-major
// to column-major and back (the map is its own inverse).
constexpr int transposed_index(int i) { return 3 * (i % 3) + i / 3; }

// One 3x3 from one order to the other (a transpose; its own inverse).
template <typename T>
void transpose3(const T* in, T* out) {
  for (int i = 0; i < 9; ++i) out[transposed_index(i)] = in[i];
}

inline std::array<double, 9> row_major_of(const std::array<double, 9>& column_major) {
  std::array<double, 9> out;
  transpose3(column_major.data(), out.data());
  return out;
}

inline std::array<double, 9> column_major_of(const std::array<double, 9>& row_major) {
  std::array<double, 9> out;
  transpose3(row_major.data(), out.data());
  return out;
}

}  // namespace snh::fem
