// Skin weights as exported: sums off 1 and unweighted vertices
// (host/character/skin_weights.h).
#include "character/skin_weights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "character/reader_messages.h"
#include "snh/error.h"

namespace snh::detail {
namespace {

// For each vertex in `wanting`, the vertex among `having` nearest to it
// (ties: the lower index), through a uniform grid over `having`.
std::vector<size_t> nearest_of(const std::vector<double>& x, const std::vector<size_t>& having,
                               const std::vector<size_t>& wanting) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t v : having)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], x[3 * v + d]);
      hi[d] = std::max(hi[d], x[3 * v + d]);
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
  const int n = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(having.size()))));
  const double h = extent / n * (1 + 1e-9);
  // Clamped before the conversion: a vertex far outside the weighted ones'
  // box (or all of those at one point) is many cells away.
  const auto cell_of = [&](const double* p, int d) {
    const double t = std::floor((p[d] - lo[d]) / h);
    return t >= n - 1 ? n - 1 : t > 0.0 ? static_cast<int>(t) : 0;
  };
  std::vector<std::vector<size_t>> grid(static_cast<size_t>(n) * n * n);
  for (size_t v : having) {
    const double* p = &x[3 * v];
    grid[(static_cast<size_t>(cell_of(p, 2)) * n + cell_of(p, 1)) * n + cell_of(p, 0)].push_back(v);
  }
  std::vector<size_t> out;
  for (size_t v : wanting) {
    const double* p = &x[3 * v];
    const int c[3] = {cell_of(p, 0), cell_of(p, 1), cell_of(p, 2)};
    double best = std::numeric_limits<double>::infinity();
    size_t best_v = having.front();
    // Rings of cells outwards until the ring's nearest possible point is
    // farther than the best found.
    for (int r = 0; r <= n; ++r) {
      if (std::isfinite(best) && (r - 1) * h > std::sqrt(best)) break;
      for (int k = c[2] - r; k <= c[2] + r; ++k)
        for (int j = c[1] - r; j <= c[1] + r; ++j)
          for (int i = c[0] - r; i <= c[0] + r; ++i) {
            if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) continue;
            if (i < 0 || j < 0 || k < 0 || i >= n || j >= n || k >= n) continue;
            for (size_t w : grid[(static_cast<size_t>(k) * n + j) * n + i]) {
              double d2 = 0.0;
              for (int d = 0; d < 3; ++d) d2 += (x[3 * w + d] - p[d]) * (x[3 * w + d] - p[d]);
              if (d2 < best || (d2 == best && w < best_v)) {
                best = d2;
                best_v = w;
              }
            }
          }
    }
    out.push_back(best_v);
  }
  return out;
}

}  // namespace

void resolve_skin_weights(Character& c, const CharacterReadOptions& options) {
  const size_t n = c.surface.vertex_count();
  SkinWeights& w = c.weights;
  if (w.vertex_count() != n)
    throw Error(c.file + ": " + std::to_string(w.vertex_count()) + " weight rows for " + std::to_string(n) +
                " surface vertices");
  std::vector<std::vector<std::pair<int32_t, double>>> rows(n);
  for (size_t v = 0; v < n; ++v)
    for (int32_t e = w.offset[v]; e < w.offset[v + 1]; ++e)
      if (w.weight[e] > 0.0) rows[v].push_back({w.joint[e], w.weight[e]});

  size_t normalized = 0;
  double worst = 1.0;
  std::vector<size_t> having, wanting;
  for (size_t v = 0; v < n; ++v) {
    auto& row = rows[v];
    std::sort(row.begin(), row.end());
    // One entry per joint: a file may name a joint twice for a vertex.
    std::vector<std::pair<int32_t, double>> merged;
    for (const auto& jw : row) {
      if (!merged.empty() && merged.back().first == jw.first)
        merged.back().second += jw.second;
      else
        merged.push_back(jw);
    }
    row = std::move(merged);
    if (row.empty()) {
      wanting.push_back(v);
      continue;
    }
    having.push_back(v);
    double sum = 0.0;
    for (const auto& jw : row) sum += jw.second;
    if (std::abs(sum - 1.0) > options.weight_tolerance) {
      if (options.weights == WeightPolicy::strict)
        throw Error(c.file + ": surface vertex " + std::to_string(v) + ": its skin weights sum to " + number(sum) +
                    ", not 1 (tolerance " + number(options.weight_tolerance) +
                    "; weights \"normalize\" divides them by their sum)");
      ++normalized;
      if (std::abs(sum - 1.0) > std::abs(worst - 1.0)) worst = sum;
    }
    for (auto& jw : row) jw.second /= sum;
  }
  if (having.empty()) throw Error(c.file + ": no skin vertex has a weight for any joint");
  if (!wanting.empty()) {
    const std::vector<size_t> source = nearest_of(c.surface.positions.xyz(), having, wanting);
    for (size_t k = 0; k < wanting.size(); ++k) rows[wanting[k]] = rows[source[k]];
    c.warnings.push_back("skin weights: " + std::to_string(wanting.size()) + " of " + std::to_string(n) +
                         " vertices have no weight; each follows its nearest weighted vertex (first: vertex " +
                         std::to_string(wanting.front()) + " follows vertex " + std::to_string(source.front()) + ")");
  }
  if (normalized > 0)
    c.warnings.push_back("skin weights: " + std::to_string(normalized) + " of " + std::to_string(n) +
                         " vertices have weights that do not sum to 1 (worst sum " + number(worst) + "); normalized");
  SkinWeights out;
  for (const auto& row : rows) {
    for (const auto& [j, x] : row) {
      out.joint.push_back(j);
      out.weight.push_back(x);
    }
    out.offset.push_back(static_cast<int32_t>(out.joint.size()));
  }
  w = std::move(out);
}

}  // namespace snh::detail
