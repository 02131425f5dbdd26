/* Squared distances between surface primitives, with their closest-feature
 * classification, gradients and Hessians in closed form: the geometry of the
 * incremental-potential barrier (Li et al. 2020, "Incremental Potential
 * Contact", sec. 4.1 and supplementary A). Shared by the host detection
 * (solver/contact/barrier_contact.h) and the device's (contact/barrier_pairs.cl).
 *
 * A pair is four vertices, 12 reals vertex-major:
 *   point-triangle  p, t0, t1, t2
 *   edge-edge       a0, a1, b0, b1
 * The squared distance between the primitives is, depending on which
 * features are closest, one of three smooth forms (IPC's distance types),
 * each written in a few difference vectors y_i = sum_v c_iv x_v (c_iv in
 * {-1, 0, 1}):
 *   point-point  f = |y|^2                                  y = q - p
 *   point-line   f = |r|^2 - (r.e)^2 / |e|^2                r = p - e0, e = e1 - e0
 *   plane        f = (r.n)^2 / |n|^2,  n = a x b            point-plane: r = p - t0, a = t1 - t0, b = t2 - t0
 *                                                           line-line:   r = a0 - b0, a = a1 - a0, b = b1 - b0
 * Gradient and Hessian in the y's (below), then to the vertices by the
 * chain rule through the constant c (ipc_to_vertices). Within one type the
 * form is smooth; across types the squared distance is C^1, as IPC uses it.
 *
 * Hessians are 12 x 12 row-major (symmetric). Degenerate input (a zero-length
 * edge, a zero-area triangle) falls back to the lower-dimensional feature in
 * the classification, so the forms never divide by zero there. */
#ifndef SNH_CONTACT_IPC_DISTANCE_H
#define SNH_CONTACT_IPC_DISTANCE_H

#include "snh_portable.h"

/* Point-triangle types: closest to vertex t0..t2, to edge (t0 t1), (t1 t2),
 * (t2 t0), or to the interior (the plane). */
#define IPC_PT_T0 0
#define IPC_PT_T1 1
#define IPC_PT_T2 2
#define IPC_PT_E0 3
#define IPC_PT_E1 4
#define IPC_PT_E2 5
#define IPC_PT_T 6
/* Edge-edge types: endpoint to endpoint, edge to endpoint, line to line. */
#define IPC_EE_A0B0 0
#define IPC_EE_A0B1 1
#define IPC_EE_A1B0 2
#define IPC_EE_A1B1 3
#define IPC_EE_AB0 4 /* edge a, point b0 */
#define IPC_EE_AB1 5
#define IPC_EE_A0B 6 /* point a0, edge b */
#define IPC_EE_A1B 7
#define IPC_EE_AB 8

SNH_FN real ipc_dot3(const real* a, const real* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
SNH_FN void ipc_cross3(const real* a, const real* b, real* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
SNH_FN void ipc_sub3(const real* a, const real* b, real* out) {
  out[0] = a[0] - b[0];
  out[1] = a[1] - b[1];
  out[2] = a[2] - b[2];
}

/* Point-point form: f = |y|^2; gy[3], hy[9]. */
SNH_FN real ipc_point_point_form(const real* y, real* gy, real* hy) {
  for (int i = 0; i < 3; ++i) {
    gy[i] = SNH_R(2) * y[i];
    for (int j = 0; j < 3; ++j) hy[3 * i + j] = i == j ? SNH_R(2) : SNH_R(0);
  }
  return ipc_dot3(y, y);
}

/* Point-line form in (r, e): f = |r|^2 - s^2 / c, s = r.e, c = e.e;
 *   df/dr = 2 r - 2 s e / c,  df/de = -2 s r / c + 2 s^2 e / c^2,
 *   H_rr = 2 I - 2 e e^T / c,
 *   H_re = -2 (e r^T + s I) / c + 4 s e e^T / c^2,
 *   H_ee = -2 r r^T / c + 4 s (r e^T + e r^T) / c^2 + 2 s^2 I / c^2 - 8 s^2 e e^T / c^3.
 * gy[6], hy[36] (6 x 6 row-major over r then e). */
SNH_FN real ipc_point_line_form(const real* r, const real* e, real* gy, real* hy) {
  const real s = ipc_dot3(r, e), c = ipc_dot3(e, e);
  for (int i = 0; i < 3; ++i) {
    gy[i] = SNH_R(2) * r[i] - SNH_R(2) * s * e[i] / c;
    gy[3 + i] = -SNH_R(2) * s * r[i] / c + SNH_R(2) * s * s * e[i] / (c * c);
    for (int j = 0; j < 3; ++j) {
      const real id = i == j ? SNH_R(1) : SNH_R(0);
      const real rr = SNH_R(2) * id - SNH_R(2) * e[i] * e[j] / c;
      const real re = -SNH_R(2) * (e[i] * r[j] + s * id) / c + SNH_R(4) * s * e[i] * e[j] / (c * c);
      const real ee = -SNH_R(2) * r[i] * r[j] / c + SNH_R(4) * s * (r[i] * e[j] + e[i] * r[j]) / (c * c) +
                      SNH_R(2) * s * s * id / (c * c) - SNH_R(8) * s * s * e[i] * e[j] / (c * c * c);
      hy[6 * i + j] = rr;
      hy[6 * i + 3 + j] = re;
      hy[6 * (3 + j) + i] = re;
      hy[6 * (3 + i) + 3 + j] = ee;
    }
  }
  return ipc_dot3(r, r) - s * s / c;
}

/* Plane form in (r, a, b): f = s^2 / c, n = a x b, s = r.n, c = n.n. In
 * (r, n): df/dr = 2 s n / c, g_n = df/dn = 2 s r / c - 2 s^2 n / c^2,
 *   H_rr = 2 n n^T / c,  H_rn = 2 (n r^T + s I) / c - 4 s n n^T / c^2,
 *   H_nn = 2 r r^T / c - 4 s (r n^T + n r^T) / c^2 - 2 s^2 I / c^2 + 8 s^2 n n^T / c^3;
 * then dn/da = -[b]x, dn/db = [a]x, and the second derivative of n adds
 * d^2 f/da db += -[g_n]x. gy[9], hy[81] (9 x 9 row-major over r, a, b). */
SNH_FN real ipc_plane_form(const real* r, const real* a, const real* b, real* gy, real* hy) {
  real n[3];
  ipc_cross3(a, b, n);
  const real s = ipc_dot3(r, n), c = ipc_dot3(n, n);
  real gw[6], hw[36];
  for (int i = 0; i < 3; ++i) {
    gw[i] = SNH_R(2) * s * n[i] / c;
    gw[3 + i] = SNH_R(2) * s * r[i] / c - SNH_R(2) * s * s * n[i] / (c * c);
    for (int j = 0; j < 3; ++j) {
      const real id = i == j ? SNH_R(1) : SNH_R(0);
      hw[6 * i + j] = SNH_R(2) * n[i] * n[j] / c;
      const real rn = SNH_R(2) * (n[i] * r[j] + s * id) / c - SNH_R(4) * s * n[i] * n[j] / (c * c);
      hw[6 * i + 3 + j] = rn;
      hw[6 * (3 + j) + i] = rn;
      hw[6 * (3 + i) + 3 + j] = SNH_R(2) * r[i] * r[j] / c - SNH_R(4) * s * (r[i] * n[j] + n[i] * r[j]) / (c * c) -
                                SNH_R(2) * s * s * id / (c * c) + SNH_R(8) * s * s * n[i] * n[j] / (c * c * c);
    }
  }
  /* J (6 x 9): w = (r, n) from z = (r, a, b); rows of n: [0, -[b]x, [a]x],
   * [v]x = [[0, -v2, v1], [v2, 0, -v0], [-v1, v0, 0]]. */
  real jac[54];
  for (int k = 0; k < 54; ++k) jac[k] = SNH_R(0);
  for (int i = 0; i < 3; ++i) jac[9 * i + i] = SNH_R(1);
  const real bx[9] = {SNH_R(0), -b[2], b[1], b[2], SNH_R(0), -b[0], -b[1], b[0], SNH_R(0)};
  const real ax[9] = {SNH_R(0), -a[2], a[1], a[2], SNH_R(0), -a[0], -a[1], a[0], SNH_R(0)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      jac[9 * (3 + i) + 3 + j] = -bx[3 * i + j];
      jac[9 * (3 + i) + 6 + j] = ax[3 * i + j];
    }
  for (int p = 0; p < 9; ++p) {
    real g = SNH_R(0);
    for (int k = 0; k < 6; ++k) g += jac[9 * k + p] * gw[k];
    gy[p] = g;
  }
  /* The upper triangle, mirrored: exactly symmetric. */
  for (int p = 0; p < 9; ++p)
    for (int q = p; q < 9; ++q) {
      real h = SNH_R(0);
      for (int k = 0; k < 6; ++k) {
        if (jac[9 * k + p] == SNH_R(0)) continue;
        real t = SNH_R(0);
        for (int l = 0; l < 6; ++l) t += hw[6 * k + l] * jac[9 * l + q];
        h += jac[9 * k + p] * t;
      }
      hy[9 * p + q] = h;
    }
  const real* gn = gw + 3;
  const real gx[9] = {SNH_R(0), -gn[2], gn[1], gn[2], SNH_R(0), -gn[0], -gn[1], gn[0], SNH_R(0)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) hy[9 * (3 + i) + 6 + j] -= gx[3 * i + j];
  for (int p = 0; p < 9; ++p)
    for (int q = 0; q < p; ++q) hy[9 * p + q] = hy[9 * q + p];
  return s * s / c;
}

/* From m difference vectors y_i = sum_v c[4 i + v] x_v (gy[3m], hy[3m x 3m])
 * to the four vertices: g[12] = C^T gy, h[144] = C^T hy C (blockwise). */
SNH_FN void ipc_to_vertices(int m, const int* c, const real* gy, const real* hy, real* g, real* h) {
  for (int v = 0; v < 4; ++v)
    for (int d = 0; d < 3; ++d) {
      real s = SNH_R(0);
      for (int i = 0; i < m; ++i) s += (real)c[4 * i + v] * gy[3 * i + d];
      g[3 * v + d] = s;
    }
  /* The upper triangle, mirrored: exactly symmetric for a symmetric hy. */
  const int n = 3 * m;
  for (int a = 0; a < 12; ++a)
    for (int b = a; b < 12; ++b) {
      const int v = a / 3, d = a % 3, w = b / 3, e = b % 3;
      real s = SNH_R(0);
      for (int i = 0; i < m; ++i) {
        if (c[4 * i + v] == 0) continue;
        for (int j = 0; j < m; ++j) s += (real)(c[4 * i + v] * c[4 * j + w]) * hy[n * (3 * i + d) + 3 * j + e];
      }
      h[12 * a + b] = s;
      h[12 * b + a] = s;
    }
}

/* The form of a type as difference vectors: *m of them, coefficients c
 * (4 per vector), and which form (0 point-point, 1 point-line, 2 plane).
 * A point-point between vertices i and j, a point-line from vertex i to
 * edge (j, k), a plane over (i; j, k, l) with r = x_i - x_j, a = x_k - x_j,
 * b = x_l - x_j (point-plane: i = p, j = t0) or, for line-line (i, j) and
 * (k, l), r = x_i - x_k, a = x_j - x_i, b = x_l - x_k. */
SNH_FN void ipc_set_point_point(int i, int j, int* c, int* m, int* form) {
  for (int k = 0; k < 12; ++k) c[k] = 0;
  c[j] = 1;
  c[i] = -1;
  *m = 1;
  *form = 0;
}
SNH_FN void ipc_set_point_line(int i, int j, int k, int* c, int* m, int* form) {
  for (int q = 0; q < 12; ++q) c[q] = 0;
  c[i] = 1;
  c[j] = -1;
  c[4 + k] = 1;
  c[4 + j] = -1;
  *m = 2;
  *form = 1;
}
SNH_FN void ipc_set_point_plane(int* c, int* m, int* form) {
  for (int q = 0; q < 12; ++q) c[q] = 0;
  c[0] = 1;
  c[1] = -1;
  c[4 + 2] = 1;
  c[4 + 1] = -1;
  c[8 + 3] = 1;
  c[8 + 1] = -1;
  *m = 3;
  *form = 2;
}
SNH_FN void ipc_set_line_line(int* c, int* m, int* form) {
  for (int q = 0; q < 12; ++q) c[q] = 0;
  c[0] = 1;
  c[2] = -1;
  c[4 + 1] = 1;
  c[4 + 0] = -1;
  c[8 + 3] = 1;
  c[8 + 2] = -1;
  *m = 3;
  *form = 2;
}

SNH_FN void ipc_pt_form(int type, int* c, int* m, int* form) {
  if (type <= IPC_PT_T2)
    ipc_set_point_point(0, 1 + type, c, m, form);
  else if (type == IPC_PT_E0)
    ipc_set_point_line(0, 1, 2, c, m, form);
  else if (type == IPC_PT_E1)
    ipc_set_point_line(0, 2, 3, c, m, form);
  else if (type == IPC_PT_E2)
    ipc_set_point_line(0, 3, 1, c, m, form);
  else
    ipc_set_point_plane(c, m, form);
}

SNH_FN void ipc_ee_form(int type, int* c, int* m, int* form) {
  if (type <= IPC_EE_A1B1)
    ipc_set_point_point(type >> 1, 2 + (type & 1), c, m, form);
  else if (type == IPC_EE_AB0)
    ipc_set_point_line(2, 0, 1, c, m, form);
  else if (type == IPC_EE_AB1)
    ipc_set_point_line(3, 0, 1, c, m, form);
  else if (type == IPC_EE_A0B)
    ipc_set_point_line(0, 2, 3, c, m, form);
  else if (type == IPC_EE_A1B)
    ipc_set_point_line(1, 2, 3, c, m, form);
  else
    ipc_set_line_line(c, m, form);
}

/* The difference vectors of a form at x. */
SNH_FN void ipc_differences(int m, const int* c, const real* x, real* y) {
  for (int i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d) {
      real s = SNH_R(0);
      for (int v = 0; v < 4; ++v) s += (real)c[4 * i + v] * x[3 * v + d];
      y[3 * i + d] = s;
    }
}

/* A form's squared distance, and when g is not null its gradient g[12] and
 * Hessian h[144] in the vertices. */
SNH_FN real ipc_form_distance(int m, const int* c, int form, const real* x, real* g, real* h) {
  real y[9], gy[9], hy[81];
  ipc_differences(m, c, x, y);
  real f;
  if (form == 0)
    f = ipc_point_point_form(y, gy, hy);
  else if (form == 1)
    f = ipc_point_line_form(y, y + 3, gy, hy);
  else
    f = ipc_plane_form(y, y + 3, y + 6, gy, hy);
  if (g) ipc_to_vertices(m, c, gy, hy, g, h);
  return f;
}

/* IPC's point-triangle classification (ipc-toolkit point_triangle_distance_type):
 * the point's coordinates along each edge e and along e x n (outward), n the
 * triangle's normal; a degenerate triangle is classified by its closest edge
 * or vertex. */
SNH_FN int ipc_pt_type(const real* x) {
  const real* p = x;
  real e0[3], e2[3], n[3];
  ipc_sub3(x + 6, x + 3, e0);
  ipc_sub3(x + 9, x + 3, e2);
  ipc_cross3(e0, e2, n);
  real along[3], out[3];
  for (int k = 0; k < 3; ++k) {
    const real* a = x + 3 + 3 * k;
    const real* b = x + 3 + 3 * ((k + 1) % 3);
    real e[3], en[3], w[3];
    ipc_sub3(b, a, e);
    ipc_cross3(e, n, en);
    ipc_sub3(p, a, w);
    const real ee = ipc_dot3(e, e), nn = ipc_dot3(en, en);
    along[k] = ee > SNH_R(0) ? ipc_dot3(w, e) / ee : SNH_R(0);
    out[k] = nn > SNH_R(0) ? ipc_dot3(w, en) / nn : SNH_R(1);
    if (along[k] > SNH_R(0) && along[k] < SNH_R(1) && out[k] >= SNH_R(0) && ee > SNH_R(0)) return IPC_PT_E0 + k;
  }
  if (along[0] <= SNH_R(0) && along[2] >= SNH_R(1)) return IPC_PT_T0;
  if (along[1] <= SNH_R(0) && along[0] >= SNH_R(1)) return IPC_PT_T1;
  if (along[2] <= SNH_R(0) && along[1] >= SNH_R(1)) return IPC_PT_T2;
  if (!(ipc_dot3(n, n) > SNH_R(0))) {
    /* Zero area: the closest of the three vertices (no plane to project on). */
    real w[3];
    ipc_sub3(p, x + 3, w);
    real best = ipc_dot3(w, w);
    int type = IPC_PT_T0;
    for (int k = 1; k < 3; ++k) {
      ipc_sub3(p, x + 3 + 3 * k, w);
      const real d = ipc_dot3(w, w);
      if (d < best) {
        best = d;
        type = k;
      }
    }
    return type;
  }
  return IPC_PT_T;
}

/* Point-segment classification of vertex i against edge (j, k) for the
 * parallel case of ipc_ee_type: 0 (j), 1 (k), 2 (interior). */
SNH_FN int ipc_point_segment_feature(const real* x, int i, int j, int k, real* distance) {
  real e[3], w[3];
  ipc_sub3(x + 3 * k, x + 3 * j, e);
  ipc_sub3(x + 3 * i, x + 3 * j, w);
  const real ee = ipc_dot3(e, e);
  const real t = ee > SNH_R(0) ? ipc_dot3(w, e) / ee : SNH_R(0);
  if (t <= SNH_R(0)) {
    *distance = ipc_dot3(w, w);
    return 0;
  }
  real v[3];
  ipc_sub3(x + 3 * i, x + 3 * k, v);
  if (t >= SNH_R(1)) {
    *distance = ipc_dot3(v, v);
    return 1;
  }
  *distance = fmax(ipc_dot3(w, w) - t * t * ee, SNH_R(0));
  return 2;
}

/* IPC's edge-edge classification (ipc-toolkit edge_edge_distance_type):
 * the clamped closest-point parameters of the two segments (Eberly); for
 * nearly parallel edges (|u x v|^2 below 1e-20 max(1, |u|^2 |v|^2)) the
 * closest of the four endpoint-to-segment features. */
SNH_FN int ipc_ee_type(const real* x) {
  real u[3], v[3], w[3], uv[3];
  ipc_sub3(x + 3, x, u);
  ipc_sub3(x + 9, x + 6, v);
  ipc_sub3(x, x + 6, w);
  const real a = ipc_dot3(u, u), b = ipc_dot3(u, v), c = ipc_dot3(v, v);
  const real d = ipc_dot3(u, w), e = ipc_dot3(v, w);
  const real big_d = a * c - b * b;
  if (a == SNH_R(0) && c == SNH_R(0)) return IPC_EE_A0B0;
  if (a == SNH_R(0)) return IPC_EE_A0B;
  if (c == SNH_R(0)) return IPC_EE_AB0;
  ipc_cross3(u, v, uv);
  if (ipc_dot3(uv, uv) < SNH_R(1e-20) * fmax(SNH_R(1), a * c)) {
    /* Parallel: the closest endpoint-to-segment feature. */
    real best, dist;
    int feature = ipc_point_segment_feature(x, 0, 2, 3, &best);
    int type = feature == 0 ? IPC_EE_A0B0 : feature == 1 ? IPC_EE_A0B1 : IPC_EE_A0B;
    feature = ipc_point_segment_feature(x, 1, 2, 3, &dist);
    if (dist < best) {
      best = dist;
      type = feature == 0 ? IPC_EE_A1B0 : feature == 1 ? IPC_EE_A1B1 : IPC_EE_A1B;
    }
    feature = ipc_point_segment_feature(x, 2, 0, 1, &dist);
    if (dist < best) {
      best = dist;
      type = feature == 0 ? IPC_EE_A0B0 : feature == 1 ? IPC_EE_A1B0 : IPC_EE_AB0;
    }
    feature = ipc_point_segment_feature(x, 3, 0, 1, &dist);
    if (dist < best) type = feature == 0 ? IPC_EE_A0B1 : feature == 1 ? IPC_EE_A1B1 : IPC_EE_AB1;
    return type;
  }
  int type = IPC_EE_AB;
  const real sn = b * e - c * d;
  real tn, td;
  if (sn <= SNH_R(0)) {
    tn = e;
    td = c;
    type = IPC_EE_A0B;
  } else if (sn >= big_d) {
    tn = e + b;
    td = c;
    type = IPC_EE_A1B;
  } else {
    tn = a * e - b * d;
    td = big_d;
  }
  if (tn <= SNH_R(0)) {
    if (-d <= SNH_R(0)) return IPC_EE_A0B0;
    if (-d >= a) return IPC_EE_A1B0;
    return IPC_EE_AB0;
  }
  if (tn >= td) {
    if (-d + b <= SNH_R(0)) return IPC_EE_A0B1;
    if (-d + b >= a) return IPC_EE_A1B1;
    return IPC_EE_AB1;
  }
  return type;
}

/* Squared distances of the primitives (classified at x), with gradient and
 * Hessian when g is not null; *type gets the distance type. */
SNH_FN real ipc_pt_distance(const real* x, int* type, real* g, real* h) {
  int c[12], m, form;
  *type = ipc_pt_type(x);
  ipc_pt_form(*type, c, &m, &form);
  return ipc_form_distance(m, c, form, x, g, h);
}
SNH_FN real ipc_ee_distance(const real* x, int* type, real* g, real* h) {
  int c[12], m, form;
  *type = ipc_ee_type(x);
  ipc_ee_form(*type, c, &m, &form);
  return ipc_form_distance(m, c, form, x, g, h);
}

/* Edge-edge mollifier input: c = |a x b|^2, a = a1 - a0, b = b1 - b0, with
 * its gradient g[12] and Hessian h[144]:
 *   dc/da = 2 |b|^2 a - 2 (a.b) b,  dc/db = 2 |a|^2 b - 2 (a.b) a,
 *   H_aa = 2 |b|^2 I - 2 b b^T,  H_bb = 2 |a|^2 I - 2 a a^T,
 *   H_ab = 4 a b^T - 2 b a^T - 2 (a.b) I. */
SNH_FN real ipc_edge_cross_squared(const real* x, real* g, real* h) {
  const int c[8] = {-1, 1, 0, 0, 0, 0, -1, 1};
  real y[6], gy[6], hy[36];
  ipc_differences(2, c, x, y);
  const real* a = y;
  const real* b = y + 3;
  const real aa = ipc_dot3(a, a), bb = ipc_dot3(b, b), ab = ipc_dot3(a, b);
  for (int i = 0; i < 3; ++i) {
    gy[i] = SNH_R(2) * bb * a[i] - SNH_R(2) * ab * b[i];
    gy[3 + i] = SNH_R(2) * aa * b[i] - SNH_R(2) * ab * a[i];
    for (int j = 0; j < 3; ++j) {
      const real id = i == j ? SNH_R(1) : SNH_R(0);
      hy[6 * i + j] = SNH_R(2) * bb * id - SNH_R(2) * b[i] * b[j];
      hy[6 * (3 + i) + 3 + j] = SNH_R(2) * aa * id - SNH_R(2) * a[i] * a[j];
      const real cross = SNH_R(4) * a[i] * b[j] - SNH_R(2) * b[i] * a[j] - SNH_R(2) * ab * id;
      hy[6 * i + 3 + j] = cross;
      hy[6 * (3 + j) + i] = cross;
    }
  }
  if (g) ipc_to_vertices(2, c, gy, hy, g, h);
  return aa * bb - ab * ab;
}

#endif
