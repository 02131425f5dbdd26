// Simulation: a mesh, materials and kinematic constraints in; positions, the
// solver's history and honest diagnostics out. Each load step (quasistatic)
// or implicit Euler time step (SolveOptions::dynamics) is one Newton solve
// with a backtracking line search on the energy; its linear systems are
// solved by conjugate gradients on the OpenCL device (the device's own CG by
// default, ViennaCL's on request or without fp64) through the matrix-free,
// eigen-projected Hessian, preconditioned by block-Jacobi or, on hex8
// lattices, geometric multigrid. Obstacles, friction and barrier
// self-contact are terms of the same energy.
//
// Simulation is the object a host application keeps: built once (options
// resolved, snh/configuration.h; kernels compiled, mesh uploaded), then
// driven frame by frame (new constraint targets and forces, solve from the
// current state, read positions, fields and reaction forces).
// QuasistaticSolver is the one-shot convenience on top.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "snh/device.h"
#include "snh/fields.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/outcomes.h"
#include "snh/regions.h"
#include "snh/surface.h"

namespace snh {

struct ResolvedConfiguration;  // snh/configuration.h

// x = rotation (X - center) + center + translation; rotation row-major
// (rotation[3 * row + col]).
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
// when set, overrides `motion`: it fills the positions of the set's vertices.
// `components` says which of x, y, z the set prescribes; the others stay
// free: {false, false, true} lets the vertices slide on their planes
// z = const (per-component constraints; a sliding plane's normal is a
// coordinate axis). A vertex component may belong to one set only.
struct ConstraintSet {
  std::string name;
  std::vector<int32_t> vertices;
  std::function<RigidTransform(double t)> motion;
  std::function<void(double t, Points& xyz)> targets;
  std::array<bool, 3> components{true, true, true};

  // Vertices held at their rest positions (in `components`; the others free).
  static ConstraintSet fixed(std::string name, std::vector<int32_t> vertices,
                             std::array<bool, 3> components = {true, true, true}) {
    return {std::move(name), std::move(vertices), {}, {}, components};
  }
  // Vertices carried by motion(t) from their rest positions.
  static ConstraintSet moving(std::string name, std::vector<int32_t> vertices,
                              std::function<RigidTransform(double t)> motion,
                              std::array<bool, 3> components = {true, true, true}) {
    return {std::move(name), std::move(vertices), std::move(motion), {}, components};
  }
  // Vertices placed where targets(t, xyz) puts them (one per vertex of the set).
  static ConstraintSet targets_of(std::string name, std::vector<int32_t> vertices,
                                  std::function<void(double t, Points& xyz)> targets,
                                  std::array<bool, 3> components = {true, true, true}) {
    return {std::move(name), std::move(vertices), {}, std::move(targets), components};
  }
};

// Text from users (scene files, the snh command line, Python strings) names
// an unset option (std::optional, empty: the library chooses) "automatic"
// (docs/design.md, "Conventions of the public API").
inline constexpr const char* kAutomatic = "automatic";
// Empty for "automatic", else parse(text).
template <typename E>
std::optional<E> parse_optional(const std::string& text, E (*parse)(const std::string&)) {
  if (text == kAutomatic) return std::nullopt;
  return parse(text);
}
// The value's name (to_string), "automatic" when empty.
template <typename E>
const char* name_or_automatic(const std::optional<E>& value) {
  return value ? to_string(*value) : kAutomatic;
}

// The Hessian products of CG; unset (SolverTuning::product): the measured
// winner for the element type, precision and device class.
enum class ProductVariant {
  cached,            // SVD and eigensystem once per Newton iteration, reused by every product
  recompute,         // SVD and eigensystem at every product
  element_matrices,  // per-element 24x24 (hex8) / 12x12 (tet4) projected matrices, once per Newton iteration
  assembled,         // 3x3 blocks per vertex pair, assembled on the device from the element matrices
};

const char* to_string(ProductVariant v);
ProductVariant parse_product_variant(const std::string& text);  // the names above

// The variant an unset product resolves to, from snh-gpu-bench throughput
// measurements (docs/performance.md); device classes not measured get `cached`.
ProductVariant default_product_variant(ElementType type, Precision precision, bool gpu);

// The preconditioner of the conjugate gradient solves; unset
// (SolverTuning::preconditioner): the measured choice, multigrid on hex8
// lattices from 5,000 DOFs, else block-Jacobi.
enum class Preconditioner {
  none,          // plain CG
  block_jacobi,  // the inverted 3x3 diagonal blocks of the projected Hessian
  multigrid,     // a geometric V-cycle on the hex8 lattice (solver/multigrid/multigrid.h); hex8 lattices only
};

const char* to_string(Preconditioner p);                       // "none", "block-jacobi", "multigrid"
Preconditioner parse_preconditioner(const std::string& text);  // the names above

// What an unset preconditioner resolves to for this mesh (docs/performance.md).
Preconditioner default_preconditioner(const Mesh& mesh);

// The variant an unset product resolves to with this preconditioner: as above,
// except multigrid on CPU devices, which reuses its hierarchy between
// linearizations (MultigridOptions::rebuild_every) and so needs no element
// matrices there: the cached linearization (docs/performance.md).
ProductVariant default_product_variant(ElementType type, Precision precision, bool gpu, Preconditioner preconditioner);

// The multigrid preconditioner's settings: a symmetric V-cycle whose levels
// are the hex8 lattice coarsened 2x per axis, Galerkin coarse operators from
// the current Newton linearization, Chebyshev smoothing over block-Jacobi
// (the same before and after the coarse correction, so CG sees a symmetric
// preconditioner) and a direct solve of the coarsest level on the host.
// The fine level inside the multigrid V-cycle (its smoothing and the residual
// restricted to the coarse levels); unset (MultigridOptions::fine_level):
// built, except with inertia, obstacles or barrier self-contact (then current).
enum class MultigridFineLevel {
  // The element matrices of the build's linearization (24x24 per element,
  // kept on the device) and their block-Jacobi blocks, reused with the
  // coarse operators until the next build (also at true-Hessian
  // linearizations): between builds the V-cycle is one fixed SPD operator,
  // its Chebyshev bound estimated once per build. Not with inertia,
  // obstacles or barrier self-contact, whose terms it does not carry.
  built,
  // The engine's product of each linearization, with the block-Jacobi
  // blocks of the build and its Chebyshev bound re-estimated (2 warm power
  // iterations) at each linearization.
  current,
};

const char* to_string(MultigridFineLevel f);                             // "built", "current"
MultigridFineLevel parse_multigrid_fine_level(const std::string& text);  // the names above

// The polynomial of the multigrid's Chebyshev smoothing over block-Jacobi
// (solver/linear/chebyshev.h); lambda below is each level's power-iteration
// estimate of lambda_max(D^-1 A). Unset (MultigridOptions::chebyshev_kind):
// the measured choice for the problem, with MultigridOptions::smoother_degree
// (resolved_smoothing below).
enum class ChebyshevKind {
  // First kind on [0.1, 1.1] lambda: the smallest largest residual factor
  // there (PETSc's default interval; Adams et al. 2003).
  first,
  // Fourth kind on [0, 1.1 lambda] (Lottes 2023, "Optimal polynomial
  // smoothers for multigrid V-cycles", Numer. Linear Algebra Appl. 30(6)):
  // the smallest largest sqrt(t) times residual factor, no lower bound.
  fourth,
  // Fourth kind with Lottes' optimized weights beta_i on the updates of x
  // (degrees 1 to 4).
  optimized_fourth,
};

const char* to_string(ChebyshevKind k);                       // "first", "fourth", "optimized-fourth"
ChebyshevKind parse_chebyshev_kind(const std::string& text);  // the names above

struct MultigridOptions {
  // Chebyshev degree of each pre- and post-smoothing (operator products
  // each), and its polynomial. Both unset by default (resolved_smoothing
  // below): degree 1 of the optimized fourth kind on
  // fine levels of fewer than 600,000 DOFs whose materials all have
  // Poisson's ratio below 0.495, degree 2 of the first kind otherwise: the
  // former measured faster below those bounds, slower above them
  // (docs/performance.md, "Multigrid smoothing (degree and kind)"). Set one
  // of the two and the other, left unset, takes the fixed default:
  // degree 2, the first kind.
  std::optional<int> smoother_degree;
  std::optional<ChebyshevKind> chebyshev_kind;
  size_t coarsest_dofs = 1000;  // coarsen until a level has at most this many DOFs
  int max_levels = 12;
  // Reuse between Newton linearizations (PETSc's SNESSetLagPreconditioner,
  // made adaptive): the coarse operators, the coarsest factor and the fine
  // block-Jacobi blocks are built at the first linearization of each load
  // step, then reused for at most `rebuild_every` linearizations in all, and
  // rebuilt sooner when a CG solve converged at less than 1 / rebuild_growth
  // of the rate (decades of residual per iteration) of the first solve after
  // the build, or when the build came from a true (not projected) Hessian.
  // A reused V-cycle stays symmetric positive definite (fine_level below
  // says what of the fine level follows each linearization). 1: rebuild at
  // every linearization; unset (default): 2 when each load step rebuilds
  // (quasistatic), 4 when the hierarchy is carried across time steps
  // (dynamics), as measured (docs/performance.md, "Multigrid rebuilds
  // (rebuild_every)"; resolved_rebuild_every below).
  std::optional<int> rebuild_every;
  double rebuild_growth = 2.0;
  // Whether each load step's first linearization rebuilds; unset: yes for
  // quasistatic load steps, no under dynamics (SolveOptions::dynamics),
  // whose time steps move the operator little and take one to three Newton
  // iterations each, so the hierarchy is carried across them and rebuilt
  // by the rules above only (docs/performance.md).
  std::optional<bool> rebuild_each_load_step;
  // Unset: built, except with inertia, obstacles or barrier self-contact
  // (then current; MultigridFineLevel).
  std::optional<MultigridFineLevel> fine_level;
  // Double precision with a built fine level: its element matrices stored in
  // float (exactly symmetric), which halves what the smoother reads at every
  // V-cycle; the fine blocks, the vectors and the coarse levels stay double
  // and CG's own operator is untouched. false: the working precision. No
  // effect in float or with fine_level current (docs/performance.md).
  bool fine_level_float = true;
  // Double precision with a built fine level: the V-cycle itself in float,
  // its vectors, its stencils (every level's operator blocks), block-Jacobi
  // inverses and transfer weights, converted at its entry and exit. The
  // builds (Galerkin products, block-Jacobi inversions, the coarsest
  // factorization) stay double, and so do CG's vectors, operator and
  // tolerances: the preconditioner is applied to float rounding, which CG
  // tolerates as it does any fixed preconditioner close to symmetric.
  // false: the V-cycle in the working precision. No effect in float or with
  // fine_level current (docs/performance.md).
  bool float_cycle = true;
  // The coarsest level's solve on the device: a Chebyshev polynomial of
  // degree 8 in the level's D^-1 A (an approximate solve, no factor), so a
  // V-cycle never waits for the host and a build reads only its smoothing
  // bounds. false (default): the level's exact LDL^T solve on the host, its
  // vector read back and written again in every V-cycle. On pocl the two
  // ran equally fast (docs/performance.md, "Coarse solve on the device"); not
  // yet measured on a GPU.
  bool coarse_solve_on_device = false;
};

// `options` with smoother_degree and chebyshev_kind set (see above) for
// a fine level of `dofs` DOFs whose stiffest material in volume has
// Poisson's ratio `poisson_ratio` (the largest over the materials).
MultigridOptions resolved_smoothing(MultigridOptions options, size_t dofs, double poisson_ratio);
// The largest small-strain Poisson's ratio lambda / (2 (lambda + mu)) over
// the materials that some element uses (Material::lame()).
double max_poisson_ratio(const MaterialMap& materials);

struct NewtonIteration {
  int step = 0;
  int iteration = 0;
  double residual_norm = 0.0;  // before this iteration's update
  double energy = 0.0;
  double step_length = 0.0;  // line-search alpha accepted (0 if none)
  int cg_iterations = 0;
  double cg_relative_residual = 0.0;
  CgStop cg_stop = CgStop::none;
  // CG's direction was replaced by the preconditioned steepest descent
  // before the line search (recovery says why); printed as cg_stop's name
  // followed by "+steepest_descent" (cg_stop_text).
  bool steepest_descent = false;
  bool projected = true;  // whether this iteration's Hessian was the PSD projection
  double seconds = 0.0;   // wall time since the solve began, at the end of this iteration
  // What the solver did to get past trouble in this iteration, in order;
  // empty if nothing (snh/outcomes.h; to_string joins them, e.g.
  // "float stagnated -> double; cg_breakdown -> steepest_descent").
  std::vector<Recovery> recovery;
};

// cg_stop's name, with "+steepest_descent" where that replaced CG's direction.
std::string cg_stop_text(const NewtonIteration& record);

enum class HessianMode {
  projected,  // always the per-element PSD projection (Smith et al. 2018, sec. 4)
  // the true Hessian once Newton takes full steps that lower the residual,
  // back to the projection for a few iterations when CG meets negative
  // curvature: quadratic instead of linear convergence near the solution
  adaptive,
};

const char* to_string(HessianMode m);                     // "projected", "adaptive"
HessianMode parse_hessian_mode(const std::string& text);  // the names above

// Implicit (backward) Euler time stepping, each step the minimization of the
// incremental potential (Simulation::solve with dynamics; docs/design.md): with h = time_step / substeps, x~ = x_n + h
// v_n,
//   E(x) = 1/(2 h^2) |x - x~|^2_M + a/(2 h) |x - x_n|^2_M
//        + Psi(x) + b/h [Psi(x) - Psi(x_n) - grad Psi(x_n)^T (x - x_n)] - f^T x,
// M the lumped mass (row-sum lumping of rho with each element's quadrature,
// snh::lumped_mass). Its gradient is M (x - x~)/h^2 + grad Psi(x) - f plus the
// Rayleigh damping force (a M + b K) v to first order in h, v = (x - x_n)/h:
// the mass term exactly, the stiffness term as the Bregman divergence of Psi
// about x_n (gradient b/h (grad Psi(x) - grad Psi(x_n)) = b K v + O(h |v|^2)),
// whose Hessian b/h K(x) reuses the elastic Hessian (projected with it).
struct DynamicsOptions {
  double time_step = 0.0;  // seconds per time step (> 0)
  double density = 0.0;    // mass per rest volume (> 0)
  struct Damping {
    double mass = 0.0;       // a, 1/s (>= 0)
    double stiffness = 0.0;  // b, s (>= 0)
  } damping;
  int substeps = 1;  // backward Euler steps of time_step / substeps per time step (>= 1)
};

// A kinematic obstacle the body cannot enter (docs/design.md). Its placement at load parameter t (as
// ConstraintSet::motion: step s of n has t = s / n) is motion(t) applied to the one given here; without a motion it
// stays.
enum class ObstacleType { plane, sphere, cylinder };
const char* to_string(ObstacleType type);  // "plane", "sphere", "cylinder"

struct Obstacle {
  ObstacleType type = ObstacleType::plane;
  // plane: a point on it; sphere: its centre; cylinder: a point on its axis.
  std::array<double, 3> point{0, 0, 0};
  // plane: its normal (the free side); cylinder: its axis (infinite both
  // ways). Normalized on use; unused for the sphere.
  std::array<double, 3> direction{0, 0, 1};
  double radius = 0.0;  // sphere and cylinder (> 0)
  std::function<RigidTransform(double t)> motion;
  // Coulomb friction coefficient against this obstacle (>= 0); unset:
  // ContactOptions::friction.
  std::optional<double> friction;

  // The obstacles by their shape (checked when a Simulation is built).
  static Obstacle plane(const std::array<double, 3>& point, const std::array<double, 3>& normal) {
    return {ObstacleType::plane, point, normal, 0.0, {}, {}};
  }
  static Obstacle sphere(const std::array<double, 3>& center, double radius) {
    return {ObstacleType::sphere, center, {0, 0, 1}, radius, {}, {}};
  }
  static Obstacle cylinder(const std::array<double, 3>& point_on_axis, const std::array<double, 3>& axis,
                           double radius) {
    return {ObstacleType::cylinder, point_on_axis, axis, radius, {}, {}};
  }
  // This obstacle moving by `placement` (see motion above), or with its own
  // friction coefficient.
  Obstacle with_motion(std::function<RigidTransform(double t)> placement) const {
    Obstacle o = *this;
    o.motion = std::move(placement);
    return o;
  }
  Obstacle with_friction(double coefficient) const {
    Obstacle o = *this;
    o.friction = coefficient;
    return o;
  }
};

// Contact with the obstacles as a penalty on every vertex in the depth
// g = thickness - phi into the layer of `thickness` about each obstacle
// (phi the signed distance): E = stiffness/2 max(g, 0)^2 per vertex and
// obstacle, C^1, with the PSD Gauss-Newton Hessian stiffness grad phi
// grad phi^T (kernels/contact/obstacle.h). stiffness is per vertex (force per
// length): a body of weight W resting on n vertices sinks W / (n stiffness)
// into the layer.
//
// self: self-collision, by self_method:
//
// barrier (the default): the incremental-potential barrier (Li et al. 2020,
// "Incremental Potential Contact"; docs/design.md): kappa b(d^2) on every
// pair of non-adjacent surface primitives (point-triangle, edge-edge; hex8
// quads as two triangles) closer than self_distance (dhat; unset: 1% of the mean
// rest surface edge length), kappa = E h^2 / dhat^3 (E the largest Young's
// modulus, h that edge length), and every Newton step limited by continuous
// collision detection, so that the surface never passes through itself.
// Detection on the host. With the multigrid preconditioner its coarse levels
// carry the barrier's diagonal blocks (docs/design.md).
//
// penalty: the reference-map penalty (Smith et al. 2018
// sec. 6; docs/design.md): a surface vertex found inside a deformed
// element not adjacent to it is pulled by a spring of self_stiffness (unset: the
// same as stiffness; force per length, like stiffness) to the deformed
// position of the closest rest-surface point of where it sits in rest space,
// E = k/2 |x_s - sum_j w_j x_j|^2, the weights frozen for a Newton
// iteration. hex8 and tet4, with or without obstacles and dynamics (not with
// the multigrid preconditioner).
//
// friction: Coulomb friction against the obstacles (each obstacle's
// Obstacle::friction, else this), lagged as in IPC (Li et al. 2020): per
// vertex and obstacle, the normal force stiffness * max(thickness - phi, 0)
// and the normal at the step's start (load step, or time step's substep),
// carried by the obstacle's motion over the step, and the dissipative
// potential mu * that force * f0(|slip|), the slip the tangential part of the
// vertex's position relative to an anchor it keeps across steps (carried by
// the obstacle; kept while the vertex sticks, dragged along where it slides,
// reset out of contact and by set_state/restart): a stiff spring (static
// friction) up to a slip of friction_slip, the kinetic force beyond
// (kernels/contact/obstacle.h). Kernels carry it (SNH_FRICTION) only
// when some obstacle's coefficient is > 0.
enum class SelfContactMethod { barrier, penalty };
// Where barrier self-contact finds its candidate pairs. Unset: on the
// device when it is a GPU (no read of x), on the host when the device is
// the CPU (its uniform grid is faster there than the device's sorts on the
// same cores). Either way the pairs, and so every result, are the same bit
// for bit.
enum class SelfBroadPhase { host, device };

struct ContactOptions {
  double stiffness = 0.0;  // > 0 when there are obstacles (or penalty self-contact without self_stiffness)
  double thickness = 0.0;  // >= 0
  bool self = false;
  SelfContactMethod self_method = SelfContactMethod::barrier;
  // Barrier's dhat (> 0); unset: 1% of the mean rest surface edge
  // (embedded: of the cell size); pairs closer at rest are left out.
  std::optional<double> self_distance;
  std::optional<double> self_stiffness;  // penalty's (> 0); unset: stiffness
  // Barrier self-contact on a surface carried by a hex8 lattice's cells (an
  // embedded surface, snh/surface.h embed) instead of the mesh's boundary
  // faces: its triangles (positions at rest) and embedding. Empty: the
  // boundary. Scene files with "embed" set it to their surface.
  TriangleSurface self_surface;
  Embedding self_embedding;
  std::optional<SelfBroadPhase> self_broad_phase;  // unset: see SelfBroadPhase
  double friction = 0.0;                           // >= 0, the obstacles' coefficient unless they set their own
  // The slip (length) below which friction sticks as a spring (> 0); unset:
  // 1% of the mesh's vertex spacing (rest volume / vertices)^(1/3).
  std::optional<double> friction_slip;
};

// The solver's defaults, written once: SolveOptions' members start from
// them, and scene files ("solver" section) and the snh command line use them
// for what they leave out, so a scene solves alike from a file, the command
// line and a program.
namespace defaults {
// Newton iterations per load step (per implicit Euler substep with
// dynamics) before the step ends with StepStatus::max_newton_iterations.
// Converged steps of the shipped scenes take up to 19; steps that cannot
// progress end earlier as `stagnated`, so the limit only cuts off slow but
// progressing solves (scenes that converge linearly set more).
inline constexpr int max_newton_iterations = 200;
// CG iterations (operator applications) per Newton iteration.
inline constexpr int max_cg_iterations = 20000;
// The device CG, its status read every 2 iterations: it stops where
// ViennaCL's CG stops and returns the same iterate for every interval
// (docs/performance.md); 0 selects ViennaCL's CG.
inline constexpr int cg_check_every = 2;  // SolverTuning::cg_check_every (docs/performance.md)
// Load steps (time steps with dynamics) per solve.
inline constexpr int load_steps = 1;
// The stopping strain (SolveOptions::strain_tolerance) in double and in
// float; float resolves J - alpha only to about FLT_EPSILON lambda / mu.
inline constexpr double strain_tolerance_double = 1e-6;
inline constexpr double strain_tolerance_float = 1e-4;
inline constexpr double strain_tolerance(Precision precision) {
  return precision == Precision::single ? strain_tolerance_float : strain_tolerance_double;
}
}  // namespace defaults

// How the solver works rather than what it solves: the linear solver, its
// preconditioner and products, the forcing terms and the line search. The
// defaults are the measured choices (docs/performance.md); a first program
// leaves them alone. SolveOptions carries them (it derives from this), so
// options.hessian and options.tuning().hessian are the same setting.
struct SolverTuning {
  int max_cg_iterations = defaults::max_cg_iterations;
  // Eisenstat-Walker (choice 2) forcing terms: eta_k = gamma (|r_k| / |r_k-1|)^2,
  // capped at eta_max.
  double forcing_gamma = 0.9;
  double forcing_max = 0.5;
  std::optional<Preconditioner> preconditioner;  // unset: see Preconditioner
  MultigridOptions multigrid;
  // Backtracking halvings the line search may take before it gives up (and
  // retries once along the preconditioned steepest-descent direction).
  int line_search_halvings = 40;
  std::optional<ProductVariant> product;  // unset: see ProductVariant
  // Mixed precision in double solves: the precision of CG's Hessian
  // products. float: the cached variant's products read a float copy of
  // each linearization and compute in float (kernels/snh_portable.h,
  // SNH_MIXED), the assembled variant's read a float copy of its blocks,
  // while CG's vectors, the residual, the energy, the linearization and the
  // preconditioners stay double, so Newton converges to double's
  // tolerance; element_matrices and recompute keep double. Unset: float,
  // measured faster (docs/performance.md, "Mixed-precision products"). Ignored in float.
  // Reported in SolveResult::product_precision.
  std::optional<Precision> product_precision;
  HessianMode hessian = HessianMode::adaptive;
  // CG with its inner products on the device tests convergence on the
  // device in every iteration and keeps the iterate that met it; the host
  // reads the status once every cg_check_every iterations (a read it waits
  // for), so up to cg_check_every - 1 iterations run past convergence for
  // nothing (SolveProfile::cg_iterations_past_convergence) and the result
  // does not depend on the interval. 0: ViennaCL's CG, which reads its
  // inner products every iteration (the previous solver, kept for
  // comparison; also what devices without fp64 use). 0 selects that solver,
  // not a choice left to the library, so this is no std::optional.
  int cg_check_every = defaults::cg_check_every;
};

// What to solve: precision, time stepping or load steps, obstacles and
// contact, stopping criteria, loads and the starting state; the solver's
// expert settings in the SolverTuning it derives from.
struct SolveOptions : SolverTuning {
  Precision precision = Precision::double_;
  // Set: solve() advances time steps of implicit Euler instead of load steps
  // (load_steps then counts time steps; loads are applied in full from the
  // first step, ramp_loads is ignored; constrained vertices follow their
  // targets at each time step, substeps interpolating linearly).
  std::optional<DynamicsOptions> dynamics;
  // Kinematic obstacles and their contact penalty (SNH_OBSTACLES kernels).
  std::vector<Obstacle> obstacles;
  ContactOptions contact;
  DeviceOptions device;
  int load_steps = defaults::load_steps;
  int max_newton_iterations = defaults::max_newton_iterations;
  // Newton stops when the L2 norm of the free-DOF force residual is below
  //   max(strain_tolerance * E * h^2 * sqrt(n), absolute_tolerance,
  //       relative_tolerance * the step's initial residual norm),
  // n the vertices in elements, h = (rest volume / n)^(1/3) their spacing and
  // E the smallest Young's modulus of the materials: the residual of a
  // strain error of strain_tolerance (a vertex force is about a stress times
  // h^2), the same for the same physics at any scale of E or of the mesh.
  // strain_tolerance unset: defaults::strain_tolerance(precision), 1e-6 in
  // double, 1e-4 in float (float's floor for nearly incompressible
  // materials), unless an absolute or relative
  // tolerance is given, which then stands alone. Each criterion is off at 0;
  // SolveResult::tolerance reports the absolute value used.
  std::optional<double> strain_tolerance;
  double absolute_tolerance = 0.0;
  double relative_tolerance = 0.0;
  // Lumped external force per vertex; empty for none.
  Points external_force;
  // Body force per rest volume (e.g. density times gravity), lumped to the
  // vertices with each element's own quadrature; added to external_force.
  std::array<double, 3> body_force{0, 0, 0};
  // Forces grow with the load: at step s of n they are the previous solve's
  // plus s/n of the change (the first solve starts from none). false: the
  // full force from the first step.
  bool ramp_loads = true;
  // Float only: when a load step does not converge in float (stagnated above
  // the tolerance, line search failed, non-finite state or the iteration
  // limit), re-solve it in double from the step's starting positions and run
  // the remaining steps in double too. Needs a device with fp64 (else a
  // warning and the float result). Reported in StepResult::precision_used,
  // StepResult::fallback and SolveResult::warnings.
  bool fallback_to_double = false;
  // A step whose end state has inverted elements (J <= 0 at some quadrature
  // point) fails: its status becomes StepStatus::inverted_elements,
  // SolveResult::converged false, and the later steps are not run. false:
  // such a step keeps its Newton status and says so in its warnings.
  bool fail_on_inverted = false;
  // Starting positions of the first step; empty: rest.
  Points initial_positions;
  // Starting velocities with dynamics; empty: zero.
  Points initial_velocities;
  // Called after every Newton iteration with its record and the positions
  // it produced, e.g. to measure error against a reference
  // as the solve runs. Downloads the positions: leave empty when not needed.
  std::function<void(const NewtonIteration&, const Points& positions)> on_iteration;

  SolverTuning& tuning() { return *this; }
  const SolverTuning& tuning() const { return *this; }
};

// Where a solve's time went, in seconds. Every second of the solve is
// charged to exactly one part (the innermost phase running; a preconditioner's
// own products and vector work count as its setup or apply), so the parts add
// up to `total`. Device work is waited for at every phase boundary, so
// queued kernels are charged to the phase that queued them.
// What a solve asked of the device, counted where the engine queues it (the
// same figures on every device): kernel launches, blocking read-backs (reads
// the host waits for: vectors, reduction partials, convergence checks) and
// the bytes copied between host and device.
struct DeviceTraffic {
  long long kernel_launches = 0;
  long long blocking_readbacks = 0;
  long long bytes_to_host = 0;
  long long bytes_to_device = 0;
  DeviceTraffic& operator+=(const DeviceTraffic& o);
};

struct SolveProfile {
  double linearization = 0.0;         // per-point SVD and eigensystem (and element matrices, assembly)
  double products = 0.0;              // Hessian products (CG's operator applications)
  double preconditioner_setup = 0.0;  // building the preconditioner from the linearization
  double preconditioner_apply = 0.0;  // z = M^-1 r, in CG and for the steepest-descent fallback
  double cg_vector_work = 0.0;        // the rest of CG: updates, dot products, curvature checks
  // Energy and force evaluations: the line search's trials and each step's
  // start, with the trial updates x + alpha p.
  double line_search_energies = 0.0;
  double transfers = 0.0;  // host <-> device reads and writes (incl. the downloads behind norms and dots)
  double other = 0.0;      // the rest: host-side Newton bookkeeping, constraint placement, statistics
  // Seconds each of the engine's OpenCL kernels ran on the device, by name
  // (from its profiling event's start to its end, so without the launch;
  // already counted in the phases above, which they break down further).
  // ViennaCL's own vector kernels (CG's updates and reductions) are not
  // listed.
  std::map<std::string, double> kernels;
  // Wall time of the solve (or step), less the time in the caller's
  // callbacks (on_iteration, progress, on_step).
  double total = 0.0;
  // Device traffic of the solve (DeviceTraffic), in all ...
  long long kernel_launches = 0;
  long long blocking_readbacks = 0;
  long long bytes_to_host = 0;
  long long bytes_to_device = 0;
  // ... and by phase, under the names of the fields above ("linearization",
  // "products", ..., "transfers", "other"). A linear solve's share is its
  // products, preconditioner_apply and cg_vector_work: divided by the CG
  // iterations, the traffic per CG iteration.
  std::map<std::string, DeviceTraffic> traffic;
  // CG iterations run after the iteration at which CG had already met its
  // tolerance (or stopped), before the host read that: the status is read
  // every SolverTuning::cg_check_every iterations, so at most that less one
  // per linear solve. Not in the CG iteration counts, which end at the
  // iteration that stopped.
  long long cg_iterations_past_convergence = 0;
  SolveProfile& operator+=(const SolveProfile& o);
};

struct StepResult {
  int step = 0;
  int newton_iterations = 0;
  int cg_iterations = 0;
  bool converged = false;
  double residual_norm = 0.0;
  StepStatus status = StepStatus::none;  // how the step's Newton solve ended (snh/outcomes.h)
  double seconds = 0.0;
  // The precision of the solve this result reports (printed "float" or "double").
  Precision precision_used = Precision::double_;
  // Empty, or what fallback_to_double did, e.g. "float stagnated after 12
  // Newton / 340 CG iterations (residual 3.1e-05); re-solved in double".
  // newton_iterations and cg_iterations then count both attempts.
  std::string fallback;
  SolveProfile profile;  // this step's share of SolveResult::profile
  // With dynamics: the simulated time at the end of this step (seconds);
  // newton_iterations and cg_iterations then sum over the substeps.
  double time = 0.0;
  // With obstacles, at the end of the step: the vertices in some obstacle's
  // contact layer, and the deepest penetration into a layer as the penalty
  // sees it, max(thickness - phi) (0 when none; above `thickness` a vertex is
  // inside the obstacle itself).
  // With ContactOptions::self, `contacts` also counts the surface vertices
  // in self-contact (self_contacts of them) and max_penetration also covers
  // their spring lengths |x_s - sum_j w_j x_j| (max_self_penetration), the
  // self-penetration as the penalty sees it.
  int contacts = 0;
  double max_penetration = 0.0;
  int self_contacts = 0;
  double max_self_penetration = 0.0;
  // Barrier self-contact, at the end of the step: the surface pairs closer
  // than dhat, their smallest distance (dhat when none; > 0: the surface
  // does not pass through itself), and the host seconds the barrier took
  // in this step (detection, CCD, assembly).
  int self_contact_pairs = 0;
  double min_self_distance = 0.0;
  double self_contact_seconds = 0.0;
  // Multigrid hierarchies built in this step's linearizations (the others
  // reused one, MultigridOptions::rebuild_every); 0 with other
  // preconditioners.
  int preconditioner_builds = 0;
  // The state at the end of the step: the smallest J over the quadrature
  // points and the elements with J <= 0 at some point.
  double min_j = 0.0;
  int inverted_elements = 0;
  // Damage the step's end state or its solve shows, each beginning with its
  // ResultWarning's name (snh/outcomes.h): inverted elements (also when
  // Newton converged), a solve that stopped short of its tolerance, a
  // vertex inside an obstacle. Empty: a clean step.
  std::vector<std::string> warnings;
};

struct SolveResult {
  Points positions;  // after the last step
  std::vector<NewtonIteration> history;
  std::vector<StepResult> steps;
  bool converged = false;
  bool cancelled = false;  // the progress callback stopped the solve; later steps were not run
  double final_residual_norm = 0.0;
  double tolerance = 0.0;     // the absolute residual norm Newton stopped at (see SolveOptions)
  double volume_ratio = 0.0;  // deformed / rest volume
  double min_j = 0.0;         // over quadrature points
  double max_j = 0.0;
  int inverted_elements = 0;  // elements with J <= 0 at some quadrature point
  double seconds = 0.0;
  SolveProfile profile;  // where `seconds` went (profile.total: seconds less the callbacks)
  // Device memory the engine held at the solve's peak: mesh, material,
  // linearization, preconditioner and solver vectors (of the float and the
  // fallback double engine together when both ran).
  size_t device_memory_bytes = 0;
  DeviceInfo device;
  std::string kernel_specialization;                             // the build-time switches of the kernels used
  ProductVariant product = ProductVariant::cached;               // the variant used (resolved)
  Preconditioner preconditioner = Preconditioner::block_jacobi;  // the one used (resolved)
  // The precision CG's products ran in (SolveOptions::product_precision as used).
  Precision product_precision = Precision::double_;
  // With multigrid: its smoothing as resolved (resolved_smoothing); empty
  // otherwise.
  std::optional<int> multigrid_smoother_degree;
  std::optional<ChebyshevKind> multigrid_chebyshev;
  // With multigrid: whether its V-cycle ran in float
  // (MultigridOptions::float_cycle as used).
  bool multigrid_float_cycle = false;
  // e.g. unused vertices (they stay where they are), and every step's
  // warnings (StepResult::warnings, naming the step).
  std::vector<std::string> warnings;
};

// Called after each load step with the step's positions (e.g. to write a .vtu).
using StepCallback = std::function<void(int step, const Points& positions)>;
// Called after every Newton update; return false to cancel the solve (the
// positions stay those of the last update, SolveResult::cancelled is set).
using ProgressCallback = std::function<bool(const NewtonIteration&)>;

// What a constraint set's vertices follow (Simulation::set_transform and
// set_positions).
enum class TargetKind {
  callbacks,  // the set's own motion/targets callbacks
  transform,  // a transform given by set_transform
  positions,  // positions given by set_positions
};

// Everything that determines a Simulation's later results
// (Simulation::checkpoint): restored into a simulation built from the same
// mesh, materials, constraint sets and options on the same device, its
// next solves give the same positions, velocities and results, bit for
// bit, as those of the simulation it was taken from.
struct SimulationState {
  // The mesh it belongs to: its vertex count and mesh_fingerprint.
  uint64_t vertex_count = 0;
  uint64_t mesh_fingerprint = 0;
  Points positions;
  Points velocities;  // with dynamics; else empty
  double time = 0.0;  // simulated time with dynamics
  // Friction's anchors, one per vertex and obstacle, vertex-major
  // (ContactOptions::friction); empty without friction.
  Points friction_anchors;
  // Per constraint set, in the simulation's order.
  struct Target {
    std::string set;  // the set's name
    TargetKind kind = TargetKind::callbacks;
    // transform: the transform last reached (when known) and the one to reach.
    RigidTransform from, to;
    bool from_known = false;
    Points positions;  // positions: one per vertex of the set
  };
  std::vector<Target> targets;
  // Loads: the lumped external force and the body force last set, and the
  // load ramp's ends (SolveOptions::ramp_loads): the total lumped force the
  // last solve reached, the one the next reaches, and the one applied at the
  // last step (one per vertex; empty for none yet).
  Points external_force;
  std::array<double, 3> body_force{0, 0, 0};
  Points force_from, force_to, force_applied;
};

// A hash (64-bit FNV-1a) of the mesh's element type, positions and element
// indices, by which a checkpoint recognizes its mesh.
uint64_t mesh_fingerprint(const Mesh& mesh);

// A simulation a host application drives frame by frame. Construction
// validates everything (snh::Error naming the input), builds the kernels and
// uploads the mesh once. The state starts at SolveOptions::initial_positions
// (else rest). Each solve() moves the constrained vertices from where they
// are to their targets in load steps and brings the body to equilibrium from
// the current state (a warm start).
//
// Targets: until set_transform/set_positions is called for it, a set follows
// its own motion/targets callback with the load parameter t = s/n of each
// solve (so the first solve does what QuasistaticSolver does). An absolute
// transform (x = T(X), X the rest position) is interpolated as a rigid motion
// from the set's previous transform (slerp of the rotation about the new
// centre, linear translation); absolute positions, and transforms whose
// matrix is not a rotation, linearly from where the vertices are.
class Simulation {
 public:
  Simulation(Mesh mesh, const MaterialMap& materials, std::vector<ConstraintSet> constraints,
             SolveOptions options = {});
  Simulation(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints, SolveOptions options = {});
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;

  // Targets and loads of the next solve (snh::Error naming the set or input).
  void set_transform(const std::string& set, const RigidTransform& transform);
  void set_positions(const std::string& set, const Points& positions);  // one per vertex of the set
  void set_external_force(const Points& lumped);                        // one per vertex; empty: none
  void set_body_force(const std::array<double, 3>& per_rest_volume);
  // Replaces the state, e.g. to restart from a saved frame.
  void set_state(const Points& positions);
  // With dynamics: replaces the velocities (empty: zero).
  void set_velocities(const Points& velocities);
  // Back to the start: SolveOptions::initial_positions (else rest), every set
  // following its own callbacks, no force applied yet.
  void restart();

  // The full state (SimulationState), e.g. to resume from it later
  // (restore) or in another process (write_checkpoint, snh/checkpoint.h).
  // The preconditioner's reuse between solves (the multigrid hierarchy
  // carried across time steps, its smoothing bounds warm-started) is not
  // state that can be saved: taking a checkpoint makes the next solve build
  // the preconditioner afresh, as restoring one does, so that this
  // simulation and any restored from the checkpoint continue identically.
  SimulationState checkpoint();
  // Replaces the state by `state`, taken from this simulation or from one
  // built from the same mesh, materials, constraint sets and options.
  // Throws snh::Error, changing nothing, for a checkpoint of another mesh
  // (vertex count or mesh_fingerprint), other constraint set names, or
  // items whose sizes do not fit this simulation (velocities with or without
  // dynamics, friction anchors with or without friction).
  void restore(const SimulationState& state);

  // load_steps: 0 for SolveOptions::load_steps. With dynamics each step is
  // a time step: the constraint targets of step s of n (as in a quasistatic
  // solve) are reached at its end, the velocities are kept between solves.
  SolveResult solve(int load_steps = 0, const ProgressCallback& progress = {}, const StepCallback& on_step = {});

  const Points& positions() const;
  // With dynamics: the velocities and the simulated time.
  const Points& velocities() const;
  double time() const;
  // Per element F, J, stresses and energy density at the current state.
  ElementFields fields() const;
  // Per constraint set, the force and torque it exerts on the body at the
  // current state (torque about the set's current centroid).
  std::vector<Reaction> reactions() const;
  // The lumped external force (external_force plus body force) of the last
  // solve's final step, one per vertex.
  const Points& applied_force() const;
  // The result of the last step solved (in a StepCallback: that step's).
  const StepResult& last_step() const;

  // An embedded surface (snh/surface.h) that takes part in contact with the
  // obstacles: each surface point p = sum_i w_i x_i of its cell's lattice
  // vertices gets the obstacles' penalty, and its force f goes to the
  // vertices as w_i f (docs/design.md). Throws snh::Error for an embedding
  // that does not fit the mesh (an element out of range, weights not 8 per
  // point or not finite). Without obstacles it changes nothing; with them
  // the contact kernel is rebuilt with the surface term. An empty embedding
  // removes the surface.
  void set_contact_surface(const Embedding& embedding);

  const Mesh& mesh() const;
  const MaterialMap& materials() const;
  const std::vector<ConstraintSet>& constraints() const;
  const DeviceInfo& device() const;
  double tolerance() const;  // the stopping test's absolute part (SolveOptions::strain_tolerance)
  // The options with every unset option chosen, each with its reason
  // (snh/configuration.h): what this simulation runs with.
  const ResolvedConfiguration& configuration() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One solve through the load steps from the initial state, as a one-shot
// call: a thin layer over Simulation. Every solve() starts again from
// SolveOptions::initial_positions (else rest).
class QuasistaticSolver {
 public:
  // Validates the mesh (snh::Error on bad input) and prepares the device.
  QuasistaticSolver(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints,
                    SolveOptions options = {});
  QuasistaticSolver(Mesh mesh, const MaterialMap& materials, std::vector<ConstraintSet> constraints,
                    SolveOptions options = {});
  ~QuasistaticSolver();
  QuasistaticSolver(QuasistaticSolver&&) noexcept;
  QuasistaticSolver& operator=(QuasistaticSolver&&) noexcept;

  // The callbacks in Simulation::solve's order.
  SolveResult solve(const ProgressCallback& progress = {}, const StepCallback& on_step = {});

  const Mesh& mesh() const;
  const DeviceInfo& device() const;
  Simulation& simulation();  // the state after the last solve: fields, reactions

 private:
  Simulation simulation_;
};

// Deformation statistics of positions x: volume ratio, min/max J over the
// quadrature points, number of elements with J <= 0 somewhere.
struct DeformationStatistics {
  double volume_ratio = 0.0;
  double min_j = 0.0;
  double max_j = 0.0;
  int inverted_elements = 0;
};
DeformationStatistics deformation_statistics(const Mesh& mesh, const Points& x);

}  // namespace snh
