/* The incremental-potential barrier on a pair's squared distance (Li et al.
 * 2020, "Incremental Potential Contact", eq. 6 in IPC's squared-distance
 * form, ipc-toolkit's barrier on d^2):
 *   b(s) = -(s - sh)^2 ln(s / sh)   for 0 < s < sh = dhat^2, 0 beyond,
 *   b'(s) = -2 (s - sh) ln(s / sh) - (s - sh)^2 / s,
 *   b''(s) = -2 ln(s / sh) - 4 (s - sh) / s + (s - sh)^2 / s^2.
 * b is C^2 at s = sh and grows without bound as s -> 0: a step that keeps
 * every distance positive (ccd.h) never crosses.
 *
 * Edge-edge pairs are mollified (sec. 4.3): nearly parallel edges have a
 * distance whose gradient is discontinuous across the edge-edge types, so
 * the pair's potential is m(c) b(d^2) with c = |a x b|^2 and
 *   m(c) = (2 - c / ex) c / ex  for c < ex,  1 beyond,
 *   ex = 1e-3 |A|^2 |B|^2 from the rest edge vectors A, B.
 * m is C^1 and vanishes as the edges become parallel, where the
 * line-line distance is undefined.
 *
 * Gradients g[12] and Hessians h[144] (row-major) over the pair's vertices,
 * without the stiffness kappa (the caller multiplies). The Hessian is the
 * true one, exactly symmetric (its upper triangle mirrored); the caller projects it to PSD (IPC, sec. 4.2). */
#ifndef SNH_CONTACT_IPC_BARRIER_H
#define SNH_CONTACT_IPC_BARRIER_H

#include "contact/ipc_distance.h"

SNH_FN real ipc_barrier(real s, real sh) {
  if (!(s < sh)) return SNH_R(0);
  const real t = s - sh;
  return -t * t * log(s / sh);
}
SNH_FN real ipc_barrier_first(real s, real sh) {
  if (!(s < sh)) return SNH_R(0);
  const real t = s - sh;
  return -SNH_R(2) * t * log(s / sh) - t * t / s;
}
SNH_FN real ipc_barrier_second(real s, real sh) {
  if (!(s < sh)) return SNH_R(0);
  const real t = s - sh;
  return -SNH_R(2) * log(s / sh) - SNH_R(4) * t / s + t * t / (s * s);
}

SNH_FN real ipc_mollifier(real c, real ex) { return c < ex ? (SNH_R(2) - c / ex) * c / ex : SNH_R(1); }
SNH_FN real ipc_mollifier_first(real c, real ex) { return c < ex ? (SNH_R(2) - SNH_R(2) * c / ex) / ex : SNH_R(0); }
SNH_FN real ipc_mollifier_second(real c, real ex) { return c < ex ? -SNH_R(2) / (ex * ex) : SNH_R(0); }

/* A point-triangle pair's barrier b(d^2) at x; when g is not null its
 * gradient and Hessian b' H_d + b'' g_d g_d^T. *distance: d^2. */
SNH_FN real ipc_pt_potential(const real* x, real sh, real* distance, real* g, real* h) {
  int type;
  real gd[12], hd[144];
  const real s = ipc_pt_distance(x, &type, gd, hd);
  *distance = s;
  if (g) {
    const real b1 = ipc_barrier_first(s, sh), b2 = ipc_barrier_second(s, sh);
    for (int i = 0; i < 12; ++i) {
      g[i] = b1 * gd[i];
      for (int j = i; j < 12; ++j) {
        h[12 * i + j] = b1 * hd[12 * i + j] + b2 * gd[i] * gd[j];
        h[12 * j + i] = h[12 * i + j];
      }
    }
  }
  return ipc_barrier(s, sh);
}

/* An edge-edge pair's mollified barrier m(c) b(d^2) at x (ex as above);
 * gradient m g_b + b g_m and Hessian
 *   m H_b + b H_m + g_m g_b^T + g_b g_m^T,
 * with g_b = b' g_d, H_b = b' H_d + b'' g_d g_d^T, g_m = m' g_c,
 * H_m = m' H_c + m'' g_c g_c^T. *distance: d^2. */
SNH_FN real ipc_ee_potential(const real* x, real sh, real ex, real* distance, real* g, real* h) {
  int type;
  real gd[12], hd[144], gc[12], hc[144];
  const real s = ipc_ee_distance(x, &type, gd, hd);
  const real c = ipc_edge_cross_squared(x, gc, hc);
  *distance = s;
  const real b = ipc_barrier(s, sh), m = ipc_mollifier(c, ex);
  if (g) {
    const real b1 = ipc_barrier_first(s, sh), b2 = ipc_barrier_second(s, sh);
    const real m1 = ipc_mollifier_first(c, ex), m2 = ipc_mollifier_second(c, ex);
    for (int i = 0; i < 12; ++i) g[i] = m * b1 * gd[i] + b * m1 * gc[i];
    for (int i = 0; i < 12; ++i)
      for (int j = i; j < 12; ++j) {
        const real hb = b1 * hd[12 * i + j] + b2 * gd[i] * gd[j];
        const real hm = m1 * hc[12 * i + j] + m2 * gc[i] * gc[j];
        h[12 * i + j] = m * hb + b * hm + m1 * b1 * (gc[i] * gd[j] + gd[i] * gc[j]);
        h[12 * j + i] = h[12 * i + j];
      }
  }
  return m * b;
}

#endif
