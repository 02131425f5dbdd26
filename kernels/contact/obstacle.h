/* Kinematic obstacles and their contact penalty, per vertex (fem.cl's
 * snh_contact_vertices and the host reference alike).
 *
 * An obstacle is a record of SNH_OBSTACLE_RECORD reals, placed in the world
 * by the host at each step (its keyframed rigid motion applied):
 *   plane:    [0, point, unit normal, 0]     phi = n . (x - p)
 *   sphere:   [1, center, 0 0 0, radius]     phi = |x - c| - R
 *   cylinder: [2, point, unit axis, radius]  phi = |(I - a a^T)(x - p)| - R
 * phi is the signed distance, positive outside, grad phi its unit gradient.
 *
 * Penalty in the depth into the contact layer of thickness d, g = d - phi:
 *   E = k/2 max(g, 0)^2,  force -dE/dx = k max(g, 0) grad phi,
 * C^1 in x (the force is continuous, zero at g = 0). Hessian, Gauss-Newton:
 *   H = k [g > 0] grad phi grad phi^T,
 * dropping -k g hess(phi) (for the sphere and cylinder, hess(phi) is PSD
 * outside the axis, so the dropped term is negative semidefinite and H is
 * PSD: the projection the notes on contact ask for; for the plane it is
 * exact).
 *
 * Coulomb friction (obstacle_friction), lagged as in IPC (Li et al. 2020,
 * "Incremental Potential Contact", sec. 5): the normal force magnitude
 * lambda = k max(d - phi0, 0) and the normal n0 are those at the step's start
 * x0 against the obstacle as it was then (its record at the step's start).
 * Each vertex keeps an anchor A per obstacle across steps (a return mapping,
 * obstacle_friction_anchor): where it sticks the anchor stays, so static
 * friction does not creep from step to step. Anchor and normal are carried
 * by the obstacle's rigid motion over the step (R, t of its friction
 * record): a = R A + t, n = R n0. The slip is the tangential part of x - a,
 *   u = (I - n n^T)(x - a),  y = |u|,
 * and the dissipative potential, a fixed function of x within the step,
 *   D = mu lambda f0(y),  f0(y) = y^2/eps - y^3/(3 eps^2) + eps/3 (y < eps),
 *                         f0(y) = y                          (y >= eps),
 * with f0' = f1, f1(y) = 2y/eps - y^2/eps^2 below eps and 1 above: static
 * friction as a stiff spring up to a slip of eps, then the kinetic force
 * mu lambda. f0 is C^2. Force -dD/dx = -mu lambda (f1(y)/y) u; Hessian, exact,
 *   mu lambda [ (f1/y) P + (f1' - f1/y) u u^T / y^2 ],  P = I - n n^T,
 * which is PSD: its eigenvalues are 0 (along n), f1/y (in the plane, normal
 * to u) and f1' >= 0 (along u). (f1' - f1/y)/y^2 is -1/(eps^2 y) below eps,
 * -1/y^3 above. */
#ifndef SNH_CONTACT_OBSTACLE_H
#define SNH_CONTACT_OBSTACLE_H

#include "snh_portable.h"

#define SNH_OBSTACLE_PLANE 0
#define SNH_OBSTACLE_SPHERE 1
#define SNH_OBSTACLE_CYLINDER 2
#define SNH_OBSTACLE_RECORD 8
/* Friction record per obstacle: [mu, R (3x3, column-major), t, 0 0 0], the
 * rigid map from the obstacle at the step's start to the obstacle now. */
#define SNH_FRICTION_RECORD 16

/* phi at x and its unit gradient n. At a sphere's centre or on a cylinder's
 * axis (no direction) n is the axis-free choice e_z (resp. any unit vector
 * normal to the axis): the depth is still right, the direction arbitrary. */
SNH_FN real obstacle_distance(SNH_GLOBAL const real* r, const real* x, real* n) {
  const int type = (int)r[0];
  real w[3];
  for (int i = 0; i < 3; ++i) w[i] = x[i] - r[1 + i];
  if (type == SNH_OBSTACLE_PLANE) {
    for (int i = 0; i < 3; ++i) n[i] = r[4 + i];
    return n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
  }
  if (type == SNH_OBSTACLE_CYLINDER) {
    const real along = r[4] * w[0] + r[5] * w[1] + r[6] * w[2];
    for (int i = 0; i < 3; ++i) w[i] -= along * r[4 + i];
  }
  const real length = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (length > SNH_R(0)) {
    for (int i = 0; i < 3; ++i) n[i] = w[i] / length;
  } else {
    /* e_z, or for a cylinder a unit vector normal to its axis. */
    const real a2 = type == SNH_OBSTACLE_CYLINDER ? r[6] : SNH_R(0);
    n[0] = SNH_R(0);
    n[1] = SNH_R(0);
    n[2] = SNH_R(1);
    if (fabs(a2) > SNH_R(0.9)) {
      n[0] = SNH_R(1);
      n[2] = SNH_R(0);
    }
    if (type == SNH_OBSTACLE_CYLINDER) {
      const real d = n[0] * r[4] + n[1] * r[5] + n[2] * r[6];
      for (int i = 0; i < 3; ++i) n[i] -= d * r[4 + i];
      const real l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int i = 0; i < 3; ++i) n[i] /= l;
    }
  }
  return length - r[7];
}

/* Sum over `count` obstacles of the penalty at vertex position x: returns the
 * energy, adds the force to force[3] and the Gauss-Newton Hessian to
 * hessian[9] (column-major), and raises *depth to the largest g = d - phi
 * (the caller starts it at 0: no contact). */
SNH_FN real obstacle_contact(SNH_GLOBAL const real* table, int count, real stiffness, real thickness, const real* x,
                             real* force, real* hessian, real* depth) {
  real energy = SNH_R(0);
  for (int o = 0; o < count; ++o) {
    real n[3];
    const real phi = obstacle_distance(table + SNH_OBSTACLE_RECORD * o, x, n);
    const real g = thickness - phi;
    if (g > SNH_R(0)) {
      energy += SNH_R(0.5) * stiffness * g * g;
      for (int i = 0; i < 3; ++i) force[i] += stiffness * g * n[i];
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) hessian[3 * c + i] += stiffness * n[i] * n[c];
      *depth = fmax(*depth, g);
    }
  }
  return energy;
}

/* An embedded surface point p = sum_i w_i x_i of its cell's 8 lattice
 * vertices (`vertices`, `weights`; snh/surface.h Embedding) in contact with
 * the obstacles (Simulation::set_contact_surface): the penalty E_p(p) of
 * obstacle_contact, shared out to the vertices. Its share on vertex
 * vertices[slot], w = weights[slot]:
 *   energy w E_p (the shares sum to E_p, as sum_i w_i = 1),
 *   force  w f_p, exactly -dE_p/dx_i,
 *   Hessian block |w| (sum_j |w_j|) H_p  in place of the exact w_i w_j H_p.
 * The block diagonal majorizes the exact (w w^T) (x) H_p, since
 * (sum_i w_i u_i)^T H (sum_i w_i u_i) <= (sum_j |w_j|) sum_i |w_i| u_i^T H u_i
 * (Cauchy-Schwarz, H PSD): it is PSD, equal to the exact term on a common
 * translation u_i = u of the cell (w >= 0), stiffer for relative motions of
 * its vertices, and it fits the per-vertex contact blocks the products,
 * block-Jacobi and the multigrid read. Newton stays a descent method; a
 * point in contact converges linearly in the relative modes. Frictionless.
 * Raises *depth to the point's largest g; returns the energy share. */
SNH_FN real surface_point_contact(SNH_GLOBAL const real* table, int count, real stiffness, real thickness,
                                  SNH_GLOBAL const real* x, SNH_GLOBAL const int* vertices,
                                  SNH_GLOBAL const real* weights, int slot, real* force, real* hessian, real* depth) {
  real p[3] = {SNH_R(0), SNH_R(0), SNH_R(0)};
  real spread = SNH_R(0);
  for (int i = 0; i < 8; ++i) {
    const int v = vertices[i];
    for (int d = 0; d < 3; ++d) p[d] += weights[i] * x[3 * v + d];
    spread += fabs(weights[i]);
  }
  real f[3] = {SNH_R(0), SNH_R(0), SNH_R(0)}, h[9];
  for (int i = 0; i < 9; ++i) h[i] = SNH_R(0);
  const real energy = obstacle_contact(table, count, stiffness, thickness, p, f, h, depth);
  const real w = weights[slot], c = fabs(w) * spread;
  for (int d = 0; d < 3; ++d) force[d] += w * f[d];
  for (int i = 0; i < 9; ++i) hessian[i] += c * h[i];
  return w * energy;
}

/* Sum over `count` obstacles of the lagged friction potential at vertex
 * position x (start position x0, anchors[3 count] per obstacle at the step's
 * start; `start` the obstacle records at the step's start, `friction` the
 * friction records): returns the energy, adds the force to force[3] and the
 * Hessian to hessian[9] (column-major). eps > 0. */
SNH_FN real obstacle_friction(SNH_GLOBAL const real* start, SNH_GLOBAL const real* friction, int count, real stiffness,
                              real thickness, real eps, const real* x0, SNH_GLOBAL const real* anchors, const real* x,
                              real* force, real* hessian) {
  real energy = SNH_R(0);
  for (int o = 0; o < count; ++o) {
    SNH_GLOBAL const real* fr = friction + SNH_FRICTION_RECORD * o;
    real n0[3];
    const real phi0 = obstacle_distance(start + SNH_OBSTACLE_RECORD * o, x0, n0);
    const real c = fr[0] * stiffness * fmax(thickness - phi0, SNH_R(0)); /* mu lambda */
    if (c > SNH_R(0)) {
      real n[3], w[3];
      for (int i = 0; i < 3; ++i) {
        n[i] = fr[1 + i] * n0[0] + fr[4 + i] * n0[1] + fr[7 + i] * n0[2];
        w[i] = x[i] - (fr[10 + i] + fr[1 + i] * anchors[3 * o] + fr[4 + i] * anchors[3 * o + 1] +
                       fr[7 + i] * anchors[3 * o + 2]);
      }
      const real along = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
      real u[3];
      for (int i = 0; i < 3; ++i) u[i] = w[i] - along * n[i];
      const real y = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      real f0, f1_y, curl;
      if (y < eps) {
        f0 = y * y / eps - y * y * y / (SNH_R(3) * eps * eps) + eps / SNH_R(3);
        f1_y = SNH_R(2) / eps - y / (eps * eps);
        curl = y > SNH_R(0) ? SNH_R(-1) / (eps * eps * y) : SNH_R(0);
      } else {
        f0 = y;
        f1_y = SNH_R(1) / y;
        curl = SNH_R(-1) / (y * y * y);
      }
      energy += c * f0;
      for (int i = 0; i < 3; ++i) force[i] -= c * f1_y * u[i];
      for (int col = 0; col < 3; ++col)
        for (int i = 0; i < 3; ++i)
          hessian[3 * col + i] +=
              c * (f1_y * ((i == col ? SNH_R(1) : SNH_R(0)) - n[i] * n[col]) + curl * u[i] * u[col]);
    }
  }
  return energy;
}

/* The anchor a vertex keeps against one obstacle for the next step, from its
 * anchor at this step's start (anchor[3]) and its position x at the end: out
 * of contact at the end (against `now`, the obstacle's record at the end),
 * x itself; in contact, the anchor carried by the obstacle's motion
 * (a = R anchor + t), dragged along the slip u (tangential to n = R n0, n0
 * the normal at x0 against `start`) to within eps of x where |u| > eps (it
 * slid: the kinetic force goes on), kept where |u| <= eps (it stuck). */
SNH_FN void obstacle_friction_anchor(SNH_GLOBAL const real* start, SNH_GLOBAL const real* friction,
                                     SNH_GLOBAL const real* now, real thickness, real eps, const real* x0,
                                     const real* anchor, const real* x, real* out) {
  real n0[3], n_now[3], n[3], a[3], u[3];
  obstacle_distance(start, x0, n0);
  const real phi = obstacle_distance(now, x, n_now);
  for (int i = 0; i < 3; ++i) {
    n[i] = friction[1 + i] * n0[0] + friction[4 + i] * n0[1] + friction[7 + i] * n0[2];
    a[i] = friction[10 + i] + friction[1 + i] * anchor[0] + friction[4 + i] * anchor[1] + friction[7 + i] * anchor[2];
  }
  const real along = n[0] * (x[0] - a[0]) + n[1] * (x[1] - a[1]) + n[2] * (x[2] - a[2]);
  for (int i = 0; i < 3; ++i) u[i] = x[i] - a[i] - along * n[i];
  const real y = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const real drag = y > eps ? (y - eps) / y : SNH_R(0);
  for (int i = 0; i < 3; ++i) out[i] = thickness - phi > SNH_R(0) ? a[i] + drag * u[i] : x[i];
}

#endif /* SNH_CONTACT_OBSTACLE_H */
