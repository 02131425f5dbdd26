// Quasistatic simulation: a mesh, a material and kinematic constraints in;
// equilibrium positions and the solver's history out. Newton with a
// backtracking line search on the energy; each linear system solved by
// ViennaCL's conjugate gradient through the matrix-free, eigen-projected
// Hessian on the OpenCL device.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "snh/device.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"

namespace snh {

// x = rotation (X - center) + center + translation; rotation column-major.
struct RigidTransform {
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 3> translation{0, 0, 0};
  std::array<double, 3> center{0, 0, 0};

  static RigidTransform identity() { return {}; }
  // Rotation by `angle` (radians) about the unit `axis` through `center`.
  static RigidTransform rotation_about(const std::array<double, 3>& axis, double angle,
                                       const std::array<double, 3>& center);
  static RigidTransform translation_by(const std::array<double, 3>& offset);
  std::array<double, 3> apply(const std::array<double, 3>& rest) const;
};

// A set of vertices whose positions are prescribed. At load parameter t in
// (0, 1] (step s of n has t = s / n) each vertex sits at motion(t) applied to
// its rest position; without a motion the vertices stay at rest. `targets`,
// when set, overrides `motion`: it fills xyz per vertex of the set.
struct ConstraintSet {
  std::string name;
  std::vector<int32_t> vertices;
  std::function<RigidTransform(double t)> motion;
  std::function<void(double t, std::vector<double>& xyz)> targets;
};

enum class ProductVariant {
  automatic,         // the measured winner for this element type, precision and device class
  cached,            // SVD and eigensystem once per Newton iteration, reused by every product
  recompute,         // SVD and eigensystem at every product
  element_matrices,  // per-element 24x24 (hex8) / 12x12 (tet4) projected matrices, once per Newton iteration
  assembled,         // a ViennaCL compressed_matrix assembled from the element matrices
};

const char* to_string(ProductVariant v);
ProductVariant parse_product_variant(const std::string& text);  // the names above

// The variant `automatic` resolves to, from snh-gpu-bench throughput
// measurements (README); device classes not measured get `cached`.
ProductVariant default_product_variant(ElementType type, Precision precision, bool gpu);

struct NewtonIteration {
  int step = 0;
  int iteration = 0;
  double residual_norm = 0.0;  // before this iteration's update
  double energy = 0.0;
  double step_length = 0.0;  // line-search alpha accepted (0 if none)
  int cg_iterations = 0;
  double cg_relative_residual = 0.0;
  std::string cg_stop;    // "converged", "max_iterations", "negative_curvature", "breakdown"
  bool projected = true;  // whether this iteration's Hessian was the PSD projection
  double seconds = 0.0;   // wall time since the solve began, at the end of this iteration
  // What the solver did to get past trouble in this iteration; empty if
  // nothing. E.g. "cg_breakdown -> steepest_descent", "non_descent ->
  // steepest_descent", "line_search_failed -> steepest_descent" (the line
  // search along CG's direction failed and the preconditioned steepest
  // descent was tried; "... failed" appended if that failed too),
  // "non_finite_residual -> shorter_step" (a trial with finite energy but a
  // non-finite residual was rejected), "float <status> -> double" (the first
  // record of a step re-solved in double, see SolveOptions::fallback_to_double).
  std::string recovery;
};

enum class HessianMode {
  projected,  // always the per-element PSD projection (Smith et al. 2018, sec. 4)
  // the true Hessian once Newton takes full steps that lower the residual,
  // back to the projection for a few iterations when CG meets negative
  // curvature: quadratic instead of linear convergence near the solution
  adaptive,
};

struct SolveOptions {
  Precision precision = Precision::double_;
  DeviceOptions device;
  int load_steps = 1;
  int max_newton_iterations = 50;
  // Stop when the L2 norm of the free-DOF force residual is below
  // max(absolute_tolerance, relative_tolerance * initial norm of the step).
  double absolute_tolerance = 1e-2;
  double relative_tolerance = 0.0;
  int max_cg_iterations = 20000;
  // Eisenstat-Walker (choice 2) forcing terms: eta_k = gamma (|r_k| / |r_k-1|)^2,
  // capped at eta_max.
  double forcing_gamma = 0.9;
  double forcing_max = 0.5;
  bool block_jacobi = true;
  // Backtracking halvings the line search may take before it gives up (and
  // retries once along the preconditioned steepest-descent direction).
  int line_search_halvings = 40;  // false: CG without preconditioner
  ProductVariant product = ProductVariant::automatic;
  HessianMode hessian = HessianMode::adaptive;
  // Lumped external force, xyz per vertex (e.g. gravity); empty for none.
  std::vector<double> external_force;
  // Float only: when a load step does not converge in float (stagnated above
  // the tolerance, line search failed, non-finite state or the iteration
  // limit), re-solve it in double from the step's starting positions and run
  // the remaining steps in double too. Needs a device with fp64 (else a
  // warning and the float result). Reported in StepResult::precision_used,
  // StepResult::fallback and SolveResult::warnings.
  bool fallback_to_double = false;
  // Starting positions of the first step (xyz per vertex); empty: rest.
  std::vector<double> initial_positions;
  // Called after every Newton iteration with its record and the positions
  // it produced (xyz per vertex), e.g. to measure error against a reference
  // as the solve runs. Downloads the positions: leave empty when not needed.
  std::function<void(const NewtonIteration&, const std::vector<double>& positions)> on_iteration;
};

struct StepResult {
  int step = 0;
  int newton_iterations = 0;
  int cg_iterations = 0;
  bool converged = false;
  double residual_norm = 0.0;
  // "converged", "max_newton_iterations", "line_search_failed", "stagnated"
  // (no 1% residual decrease in 8 iterations: the precision floor), "non_finite_state"
  std::string status;
  double seconds = 0.0;
  // "float" or "double": the precision of the solve this result reports.
  std::string precision_used;
  // Empty, or what fallback_to_double did, e.g. "float stagnated after 12
  // Newton / 340 CG iterations (residual 3.1e-05); re-solved in double".
  // newton_iterations and cg_iterations then count both attempts.
  std::string fallback;
};

struct SolveResult {
  std::vector<double> positions;  // xyz per vertex, after the last step
  std::vector<NewtonIteration> history;
  std::vector<StepResult> steps;
  bool converged = false;
  double final_residual_norm = 0.0;
  double volume_ratio = 0.0;  // deformed / rest volume
  double min_j = 0.0;         // over quadrature points
  double max_j = 0.0;
  int inverted_elements = 0;  // elements with J <= 0 at some quadrature point
  double seconds = 0.0;
  DeviceInfo device;
  std::string kernel_specialization;                // the build-time switches of the kernels used
  ProductVariant product = ProductVariant::cached;  // the variant used (automatic resolved)
  std::vector<std::string> warnings;                // e.g. unused vertices (they stay where they are)
};

// Called after each load step with the step's positions (e.g. to write a .vtu).
using StepCallback = std::function<void(int step, const std::vector<double>& positions)>;

class QuasistaticSolver {
 public:
  // Validates the mesh (snh::Error on bad input) and prepares the device.
  QuasistaticSolver(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints,
                    SolveOptions options = {});
  // Regions with their own materials (snh/regions.h); also validates the map.
  QuasistaticSolver(Mesh mesh, MaterialMap materials, std::vector<ConstraintSet> constraints,
                    SolveOptions options = {});
  ~QuasistaticSolver();
  QuasistaticSolver(QuasistaticSolver&&) noexcept;
  QuasistaticSolver& operator=(QuasistaticSolver&&) noexcept;

  SolveResult solve(const StepCallback& on_step = {});

  const Mesh& mesh() const;
  const DeviceInfo& device() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Checks constraint sets (non-empty, vertices in range) and solve options
// (initial positions, steps, limits, tolerances); throws snh::Error naming
// the set or option at fault. QuasistaticSolver calls it on construction.
void validate_solve_inputs(const Mesh& mesh, const std::vector<ConstraintSet>& constraints,
                           const SolveOptions& options);

// Writes every constrained vertex's target at load parameter t into x (xyz
// per vertex): `targets` if set, else `motion(t)` applied to the rest
// position, else the rest position. Throws snh::Error for a wrong-sized
// targets callback or a non-finite target.
void apply_constraints(const Mesh& mesh, const std::vector<ConstraintSet>& constraints, double t,
                       std::vector<double>& x);

// Deformation statistics of positions x: volume ratio, min/max J over the
// quadrature points, number of elements with J <= 0 somewhere.
struct DeformationStatistics {
  double volume_ratio = 0.0;
  double min_j = 0.0;
  double max_j = 0.0;
  int inverted_elements = 0;
};
DeformationStatistics deformation_statistics(const Mesh& mesh, const std::vector<double>& x);

}  // namespace snh
