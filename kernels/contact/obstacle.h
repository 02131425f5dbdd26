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
 * exact). */
#ifndef SNH_CONTACT_OBSTACLE_H
#define SNH_CONTACT_OBSTACLE_H

#include "snh_portable.h"

#define SNH_OBSTACLE_PLANE 0
#define SNH_OBSTACLE_SPHERE 1
#define SNH_OBSTACLE_CYLINDER 2
#define SNH_OBSTACLE_RECORD 8

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

#endif /* SNH_CONTACT_OBSTACLE_H */
