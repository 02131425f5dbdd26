#include "geometry/exact_predicates.h"

#include <atomic>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <limits>

namespace snh::geometry {
namespace {

using boost::multiprecision::cpp_int;

// Shewchuk's epsilon: half an ulp of 1, so that fl(a op b) = (a op b)(1 + d), |d| <= epsilon.
constexpr double epsilon = 0x1p-53;
constexpr double orient2d_bound = (3.0 + 16.0 * epsilon) * epsilon;
constexpr double orient3d_bound = (7.0 + 56.0 * epsilon) * epsilon;
// Shewchuk's bounds hold without underflow. A product that underflows errs
// by at most 2^-1075 absolutely; in orient3d such an error is then scaled by
// one of |adz|, |bdz|, |cdz|. 2^-1000 per unit of those magnitudes covers
// every such term many times over and is far below any decided determinant.
constexpr double underflow_slack = 0x1p-1000;

std::atomic<uint64_t> fallbacks{0};

// The inputs as integers sharing one power of two: v = m * 2^(e - lowest),
// so that every determinant of them is a positive multiple of the exact one.
template <int N>
void to_integers(const double (&v)[N], cpp_int (&out)[N]) {
  int lowest = std::numeric_limits<int>::max();
  int exponent[N];
  int64_t mantissa[N];
  for (int i = 0; i < N; ++i) {
    int e = 0;
    const double f = std::frexp(v[i], &e);
    mantissa[i] = int64_t(std::ldexp(f, 53));  // exact: f has at most 53 significant bits
    exponent[i] = e - 53;
    if (mantissa[i] != 0 && exponent[i] < lowest) lowest = exponent[i];
  }
  for (int i = 0; i < N; ++i) {
    out[i] = mantissa[i];
    if (mantissa[i] != 0) out[i] <<= unsigned(exponent[i] - lowest);
  }
}

int sign_of(const cpp_int& x) { return x.sign(); }

int exact_orient2d(const double a[2], const double b[2], const double c[2]) {
  const double v[6] = {a[0], a[1], b[0], b[1], c[0], c[1]};
  cpp_int n[6];
  to_integers(v, n);
  const cpp_int acx = n[0] - n[4], acy = n[1] - n[5], bcx = n[2] - n[4], bcy = n[3] - n[5];
  return sign_of(acx * bcy - acy * bcx);
}

int exact_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]) {
  const double v[12] = {a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]};
  cpp_int n[12];
  to_integers(v, n);
  const cpp_int adx = n[0] - n[9], ady = n[1] - n[10], adz = n[2] - n[11];
  const cpp_int bdx = n[3] - n[9], bdy = n[4] - n[10], bdz = n[5] - n[11];
  const cpp_int cdx = n[6] - n[9], cdy = n[7] - n[10], cdz = n[8] - n[11];
  const cpp_int det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  return sign_of(det);
}

}  // namespace

int orient2d(const double a[2], const double b[2], const double c[2]) {
  const double acx = a[0] - c[0], bcx = b[0] - c[0];
  const double acy = a[1] - c[1], bcy = b[1] - c[1];
  const double detleft = acx * bcy;
  const double detright = acy * bcx;
  const double det = detleft - detright;
  const double bound = orient2d_bound * (std::fabs(detleft) + std::fabs(detright)) + underflow_slack;
  if (std::isfinite(det) && std::isfinite(bound)) {
    if (det > bound) return 1;
    if (-det > bound) return -1;
  }
  fallbacks.fetch_add(1, std::memory_order_relaxed);
  return exact_orient2d(a, b, c);
}

int orient3d(const double a[3], const double b[3], const double c[3], const double d[3]) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  const double bound =
      orient3d_bound * permanent + underflow_slack * (1.0 + std::fabs(adz) + std::fabs(bdz) + std::fabs(cdz));
  if (std::isfinite(det) && std::isfinite(bound)) {
    if (det > bound) return 1;
    if (-det > bound) return -1;
  }
  fallbacks.fetch_add(1, std::memory_order_relaxed);
  return exact_orient3d(a, b, c, d);
}

uint64_t exact_predicate_fallbacks() { return fallbacks.load(std::memory_order_relaxed); }

}  // namespace snh::geometry
