/* Conservative continuous collision detection for point-triangle and
 * edge-edge pairs moving linearly, x(t) = x0 + t dx: additive CCD (Li et
 * al. 2021, "Codimensional Incremental Potential Contact", sec. 5, Alg. 1).
 *
 * With the mean displacement removed (distances are invariant under a
 * common translation), no distance between the primitives can shrink
 * faster than l_p = |dp| + max_i |dt_i| (point-triangle) or
 * max |da_i| + max |db_i| (edge-edge) per unit t. So from a distance d the
 * pair advances by t_l = s d / l_p (s = 0.9, the conservative rescaling)
 * without touching, and the distance is re-evaluated; after the first
 * advance it stops when the distance falls below the gap g = (1 - s) d0,
 * returning the last t reached before (whose distance is >= g up to rounding): a time of impact that leaves at least g
 * of separation and lies before any contact. No hit within [0, tmax]: returns tmax (1 - nothing in the way). Distances
 * here are true (classified) distances, ipc_distance.h.
 *
 * A motion that starts in contact (d0 = 0) returns 0. The iterations are
 * capped (SNH_CCD_MAX_ITERATIONS): the t reached so far is still safe, so
 * the cap only shortens the step. */
#ifndef SNH_CONTACT_CCD_H
#define SNH_CONTACT_CCD_H

#include "contact/ipc_distance.h"

#define SNH_CCD_RESCALING 0.9
#define SNH_CCD_MAX_ITERATIONS 10000

/* The four displacements less their mean. */
SNH_FN void ccd_center(const real* dx, real* out) {
  for (int d = 0; d < 3; ++d) {
    const real mean = (dx[d] + dx[3 + d] + dx[6 + d] + dx[9 + d]) / SNH_R(4);
    for (int v = 0; v < 4; ++v) out[3 * v + d] = dx[3 * v + d] - mean;
  }
}

SNH_FN real ccd_norm3(const real* v) { return sqrt(ipc_dot3(v, v)); }

/* Additive CCD along x0 + t dx; `edge_edge` picks the distance and the
 * bound l_p. */
SNH_FN real ccd_additive(const real* x0, const real* dx_in, int edge_edge, real tmax) {
  real dx[12], x[12];
  ccd_center(dx_in, dx);
  real lp;
  if (edge_edge)
    lp = fmax(ccd_norm3(dx), ccd_norm3(dx + 3)) + fmax(ccd_norm3(dx + 6), ccd_norm3(dx + 9));
  else
    lp = ccd_norm3(dx) + fmax(ccd_norm3(dx + 3), fmax(ccd_norm3(dx + 6), ccd_norm3(dx + 9)));
  if (!(lp > SNH_R(0))) return tmax;
  int type;
  for (int i = 0; i < 12; ++i) x[i] = x0[i];
  real d = sqrt(edge_edge ? ipc_ee_distance(x, &type, 0, 0) : ipc_pt_distance(x, &type, 0, 0));
  if (!(d > SNH_R(0))) return SNH_R(0);
  const real gap = (SNH_R(1) - SNH_R(SNH_CCD_RESCALING)) * d;
  real t = SNH_R(0);
  for (int it = 0; it < SNH_CCD_MAX_ITERATIONS; ++it) {
    real next = t + SNH_R(SNH_CCD_RESCALING) * d / lp;
    const int last = next >= tmax;
    if (last) next = tmax;
    for (int i = 0; i < 12; ++i) x[i] = x0[i] + next * dx[i];
    d = sqrt(edge_edge ? ipc_ee_distance(x, &type, 0, 0) : ipc_pt_distance(x, &type, 0, 0));
    /* The first advance always stands (it closes at most s d0, leaving
     * (1 - s) d0 = gap); afterwards a distance below the gap stops. */
    if (d < gap && t > SNH_R(0)) return t;
    if (last) return tmax;
    t = next;
  }
  return t;
}

SNH_FN real ccd_point_triangle(const real* x0, const real* dx, real tmax) { return ccd_additive(x0, dx, 0, tmax); }
SNH_FN real ccd_edge_edge(const real* x0, const real* dx, real tmax) { return ccd_additive(x0, dx, 1, tmax); }

#endif
