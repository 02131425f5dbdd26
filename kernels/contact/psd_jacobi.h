/* The nearest positive semi-definite matrix of a symmetric 12 x 12 pair
 * Hessian (IPC, Li et al. 2020, sec. 4.2): its negative eigenvalues clamped
 * to 0. The eigen-decomposition is the cyclic Jacobi method (Golub and Van
 * Loan, "Matrix Computations", sec. 8.5.2): sweeps over the off-diagonal
 * entries in row order, each zeroed by the rotation with the smaller angle
 * (tan = sgn(theta) / (|theta| + sqrt(theta^2 + 1)), theta = (a_qq - a_pp) /
 * (2 a_pq)), until the off-diagonal part is below SNH_EPS of the whole in
 * Frobenius norm. Written once: the host (solver/contact/barrier_contact.cpp) and
 * the device (contact/barrier_pairs.cl) project alike; Eigen's solver is
 * only the tests' reference. Quadratic convergence makes 6 to 10 sweeps
 * the rule; SNH_JACOBI_MAX_SWEEPS bounds a pathological input. */
#ifndef SNH_CONTACT_PSD_JACOBI_H
#define SNH_CONTACT_PSD_JACOBI_H

#define SNH_JACOBI_N 12
#define SNH_JACOBI_MAX_SWEEPS 50

/* a (row-major, symmetric, overwritten): on return its diagonal holds the
 * eigenvalues; v: the eigenvectors as columns (row-major). */
SNH_FN_LARGE void jacobi_eigen12(real* a, real* v) {
  const int n = SNH_JACOBI_N;
  for (int i = 0; i < n * n; ++i) v[i] = SNH_R(0);
  for (int i = 0; i < n; ++i) v[(n + 1) * i] = SNH_R(1);
  real total = SNH_R(0);
  for (int i = 0; i < n * n; ++i) total += a[i] * a[i];
  const real stop = SNH_EPS * SNH_EPS * total;
  for (int sweep = 0; sweep < SNH_JACOBI_MAX_SWEEPS; ++sweep) {
    real off = SNH_R(0);
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += SNH_R(2) * a[n * p + q] * a[n * p + q];
    if (!(off > stop)) return;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const real apq = a[n * p + q];
        if (apq == SNH_R(0)) continue;
        const real theta = (a[n * q + q] - a[n * p + p]) / (SNH_R(2) * apq);
        const real t = (theta < SNH_R(0) ? SNH_R(-1) : SNH_R(1)) / (fabs(theta) + hypot(theta, SNH_R(1)));
        const real c = SNH_R(1) / sqrt(t * t + SNH_R(1)), s = t * c;
        for (int k = 0; k < n; ++k) { /* A J: columns p and q */
          const real akp = a[n * k + p], akq = a[n * k + q];
          a[n * k + p] = c * akp - s * akq;
          a[n * k + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) { /* J^T (A J): rows p and q */
          const real apk = a[n * p + k], aqk = a[n * q + k];
          a[n * p + k] = c * apk - s * aqk;
          a[n * q + k] = s * apk + c * aqk;
        }
        a[n * p + q] = SNH_R(0);
        a[n * q + p] = SNH_R(0);
        for (int k = 0; k < n; ++k) { /* V J */
          const real vkp = v[n * k + p], vkq = v[n * k + q];
          v[n * k + p] = c * vkp - s * vkq;
          v[n * k + q] = s * vkp + c * vkq;
        }
      }
  }
}

/* h (12 x 12, row-major): symmetrized, then V max(Lambda, 0) V^T where an
 * eigenvalue is negative, else left as it is (a PSD input is unchanged, as
 * the host reference leaves it). */
SNH_FN_LARGE void psd_project12(real* h) {
  const int n = SNH_JACOBI_N;
  real a[SNH_JACOBI_N * SNH_JACOBI_N], v[SNH_JACOBI_N * SNH_JACOBI_N];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a[n * i + j] = SNH_R(0.5) * (h[n * i + j] + h[n * j + i]);
  jacobi_eigen12(a, v);
  int negative = 0;
  for (int k = 0; k < n; ++k) negative |= a[(n + 1) * k] < SNH_R(0);
  if (!negative) return;
  for (int k = 0; k < n; ++k) a[k] = fmax(a[(n + 1) * k], SNH_R(0)); /* the clamped eigenvalues in a[0..n) */
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) {
      real sum = SNH_R(0);
      for (int k = 0; k < n; ++k) sum += v[n * i + k] * a[k] * v[n * j + k];
      h[n * i + j] = sum;
      h[n * j + i] = sum;
    }
}

#endif
