#include "solver/multigrid/multigrid.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "device/kernel_args.h"
#include "device/readback.h"
#include "fem/vertex_slots.h"
#include "snh/error.h"
#include "solver/linear/chebyshev.h"
#include "solver/model/block_stencil.h"
#include "viennacl/linalg/norm_2.hpp"

namespace snh::solver {

namespace {

using device::KernelArgs;

constexpr int kCellMatrix = 24 * 24;
// Power iterations for lambda_max(D^-1 A): from the fixed start, and warm
// from the last estimate, whose operator changed by a Newton step or two.
// Warm starts take 2, measured faster than 4 (docs/performance.md, "Multigrid
// power iterations (warm 2)").
constexpr int kPowerIterations = 10, kWarmPowerIterations = 2;
// The coarsest level's solve on the device: first-kind Chebyshev of degree
// 8 on [1.1 lambda / 60, 1.1 lambda] (lambda its lambda_max(D^-1 A)
// estimate), chosen by Newton and CG counts against the factor's exact
// solve and other degrees and intervals (docs/performance.md, "Coarse solve
// on the device").
constexpr int kCoarseDegree = 8;
constexpr double kUpperBound = 1.1, kCoarseSpread = 60.0;

// The model's per-vertex terms (has_vertex_terms; snh_galerkin_vertex_terms).
template <typename Real>
bool has_vertex_terms(const ElasticModel<Real>& model) {
  return solver::has_vertex_terms(model.terms());
}

// Whether the options and the model's terms give a built fine level.
template <typename Real>
bool builds_fine_level(const ElasticModel<Real>& model, const MultigridOptions& options) {
  return options.fine_level == MultigridFineLevel::built || (!options.fine_level && !has_vertex_terms(model));
}

}  // namespace

// What MultigridPreconditioner forwards to: the levels in one precision.
template <typename Real>
class MultigridPreconditioner<Real>::Cycle {
 public:
  using WideBase = viennacl::vector_base<Real>;
  virtual ~Cycle() = default;
  virtual void setup() = 0;
  virtual void update_fine_bound() = 0;
  virtual void forget_estimates() = 0;
  virtual bool fine_level_built() const = 0;
  virtual bool float_cycle() const = 0;
  virtual void apply(WideBase& z) const = 0;
  virtual const LatticeHierarchy& hierarchy() const = 0;
  virtual const MultigridOptions& options() const = 0;
  virtual int levels() const = 0;
  virtual std::vector<Real> level_matrices(int level) const = 0;
  virtual void level_product(int level, const WideBase& p, WideBase& y) const = 0;
  virtual std::vector<double> eigenvalue_estimates() const = 0;
  virtual size_t memory_bytes() const = 0;
};

namespace {

// The hierarchy of a solve in precision Real whose V-cycle runs in C: Real
// itself, or float in a double solve (MultigridOptions::float_cycle). The
// builds (Galerkin products, block-Jacobi inversions, the coarsest factor)
// run in Real, or read the fine level's float matrices; what the V-cycle
// reads at each application (stencils, inverse blocks, masks, transfer
// weights, its vectors) is stored in C.
template <typename Real, typename C>
class Levels final : public MultigridPreconditioner<Real>::Cycle {
 public:
  using VectorBase = viennacl::vector_base<C>;
  using WideBase = viennacl::vector_base<Real>;
  static constexpr bool kNarrow = !std::is_same_v<Real, C>;

  Levels(ElasticModel<Real>& model, const Mesh& mesh, const std::vector<char>& mask, const MultigridOptions& options);

  void setup() override;
  void update_fine_bound() override;
  void forget_estimates() override {
    for (auto& level : levels_) level->estimated = false;
  }
  bool fine_level_built() const override { return fine_built_; }
  bool float_cycle() const override { return kNarrow; }
  void apply(WideBase& z) const override;
  const LatticeHierarchy& hierarchy() const override { return hierarchy_; }
  const MultigridOptions& options() const override { return options_; }
  int levels() const override { return static_cast<int>(hierarchy_.levels.size()); }
  std::vector<Real> level_matrices(int level) const override;
  void level_product(int level, const WideBase& p, WideBase& y) const override;
  std::vector<double> eigenvalue_estimates() const override;
  size_t memory_bytes() const override;

 private:
  struct Level;
  void product(int level, const VectorBase& p, VectorBase& y) const;
  void inverse_diagonal(int level, VectorBase& z) const;  // z <- D^-1 z
  // Chebyshev smoothing of A x = b at `level`; r holds b - A x on entry, or
  // with `from` x = 0 and r = *from are taken as the entry values (neither
  // read); r holds the residual on return if want_residual.
  // `polynomial`: other steps than the level's smoothing (their degree).
  void chebyshev(int level, VectorBase& x, VectorBase& r, bool want_residual, const VectorBase* from = nullptr,
                 const ChebyshevSteps* polynomial = nullptr) const;
  void vcycle(int level) const;
  void coarse_solve() const;
  void factor_coarsest();
  // lambda_max(D^-1 A) by power iteration at levels [first, first + count),
  // with one read for them all on the device.
  void estimate_bounds(size_t first, size_t count);
  void estimate_on_host(Level& level, size_t l);  // no fp64: the norms read at every step
  void queue_estimate(Level& level, size_t l, int slot);
  void set_bound(Level& level, double lambda);
  void block_jacobi(Level& level);   // level.inverse from level.blocks
  void assemble_stencil(int level);  // the level's stencil from its matrices
  // r <- base - A p at an assembled level (base may be r).
  void residual(int level, const VectorBase& p, const VectorBase& base, VectorBase& r) const;
  // to <- from in the other precision (kNarrow only): snh_narrow, snh_widen.
  void convert(const device::Kernel& k, cl_mem from, size_t values, cl_mem to) const;
  // Construction's phases: the shared kernels, and each level's tables.
  void build_kernels(const Mesh& mesh, const MultigridOptions& options);
  std::unique_ptr<Level> make_level(size_t l);
  // The V-cycle's kernel switches: the coarse ones, in float for a float cycle.
  device::KernelConfig cycle_config() const {
    const device::KernelConfig& coarse = model_.data().elastic_config;
    return kNarrow ? coarse.with_float_cycle() : coarse;
  }

  ElasticModel<Real>& model_;
  device::OpenClContext& cl_;
  MultigridOptions options_;
  LatticeHierarchy hierarchy_;
  std::vector<std::unique_ptr<Level>> levels_;

  // Builds in Real: Galerkin products, block-Jacobi inversions. The
  // V-cycle's kernels in C.
  device::Kernel galerkin_cache_k_, galerkin_matrices_k_, jacobi_setup_k_;
  device::Kernel prolong_k_, restrict_k_, chebyshev_start_k_;
  device::Kernel narrow_k_, widen_k_;  // kNarrow
  // The assembled levels' kernels (they read the level's stencil): the
  // assembly in the build's precision (float matrices on a float fine
  // level), the others in C.
  struct StencilKernels {
    device::Kernel assemble, product, residual, step;
  };
  // Each level's, built for its width (stencil_build) and, on a
  // float fine level, its float matrices.
  const StencilKernels& stencil_kernels(int level) const;
  // Inertia, obstacle contact or the barrier's diagonal blocks in the fine
  // operator: added to the first coarse level's cell matrices
  // (snh_galerkin_vertex_terms) with each vertex's share 1 / (cells around it).
  bool vertex_terms_ = false;
  bool fine_built_ = false;
  // The built fine level's matrices in float (double builds).
  bool fine_float_ = false;
  device::Kernel fine_float_galerkin_k_;
  device::Kernel galerkin_vertex_k_;
  device::Buffer vertex_share_;
  device::Buffer octant_weights_;  // lattice_hierarchy.h's octant_weights()
  // kNarrow: block-Jacobi's inverse blocks in Real, narrowed into a level's
  // (the largest level's size, shared).
  device::Buffer wide_inverse_;
  size_t table_bytes_ = 0;  // its device memory
  // The coarsest level's assembled matrix (its pattern fixed at
  // construction), where each of its cell matrices' entries and each DOF's
  // diagonal sit among its values, and its factor.
  Eigen::SparseMatrix<double> coarsest_matrix_;
  std::vector<int> coarsest_slots_, coarsest_diagonal_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarsest_;
  bool coarsest_ok_ = false;
  mutable std::vector<C> host_rhs_;
  // The coarsest solve on the device (MultigridOptions::coarse_solve_on_device):
  // a Chebyshev polynomial in D^-1 A of the level (Level::solve_steps), so
  // that a V-cycle never waits for the host and a build needs no factor.
  bool coarse_on_device_ = false;
  // The power iteration's norms on the device (kernels/cg.cl).
  static constexpr size_t kPowerSpan = 4096;  // SNH_CG_SPAN of its kernels
  device::Kernel power_dot_k_, power_normalize_k_;
  mutable device::Buffer power_partials_;
  // Each estimated level's sum of squares, totalled on the device
  // (kernels/reduce.cl, the partials in index order as the host added them)
  // and read together: one read per set-up whatever the levels and steps.
  device::Kernel power_total_k_;
  device::Buffer power_totals_;
};

template <typename Real, typename C>
struct Levels<Real, C>::Level {
  size_t cells = 0, vertices = 0;
  cl_mem element_handle = nullptr;  // the level's elements (the model's at level 0)
  // mask: the builds' (Real); cycle_mask: the V-cycle's (C; with kNarrow
  // only, else mask serves).
  device::Buffer elements, offsets, adjacency, mask, cycle_mask, matrices, blocks, inverse, children;
  cl_mem cycle_mask_handle() const { return kNarrow ? cycle_mask.get() : mask.get(); }
  // The operator's blocks per vertex (snh_stencil_assemble), whose they are
  // and what they add up.
  device::Buffer neighbours, part_offsets, parts, stencil;
  int width = 0;
  StencilKernels stencil_kernels;  // built for this level's width and matrices
  device::Buffer prolong_vertices, prolong_weights, restrict_offsets, restrict_vertices, restrict_weights;
  viennacl::vector<C> b, x, r, d, t, d_next;
  viennacl::vector<C> eigenvector;  // of D^-1 A, the last power iteration's
  // Whether eigenvector holds an estimate to start from. (Assigning an empty
  // ViennaCL vector to a sized one leaves it as it was: this says instead.)
  bool estimated = false;
  double lambda = 1.0;
  ChebyshevSteps steps;        // the smoothing's coefficients for lambda (estimate_bounds)
  ChebyshevSteps solve_steps;  // the coarsest level's polynomial solve (coarse_solve)
  size_t bytes = 0;
};

template <typename Real, typename C>
const typename Levels<Real, C>::StencilKernels& Levels<Real, C>::stencil_kernels(int level) const {
  return levels_[level]->stencil_kernels;
}

// The options' limits and what the model's terms allow; throws snh::Error.
template <typename Real>
void check_multigrid_options(const ElasticModel<Real>& model, const MultigridOptions& options) {
  if (options.smoother_degree && (*options.smoother_degree < 1 || *options.smoother_degree > 16))
    throw Error("multigrid: smoother_degree must be in 1..16 (unset: automatic), got " +
                std::to_string(*options.smoother_degree));
  if (options.max_levels < 2) throw Error("multigrid: max_levels must be at least 2");
  if (options.rebuild_every && *options.rebuild_every < 1)
    throw Error(
        "multigrid: rebuild_every must be unset (automatic) or at least 1 (1: rebuild at every linearization), "
        "got " +
        std::to_string(*options.rebuild_every));
  if (!(options.rebuild_growth >= 1.0))
    throw Error("multigrid: rebuild_growth must be at least 1, got " + std::to_string(options.rebuild_growth));
  if (model.terms().self_contact)
    throw Error(
        "multigrid: its coarse levels do not carry the self-contact penalty's springs (use block-jacobi, or the "
        "barrier)");
  if (options.fine_level == MultigridFineLevel::built && has_vertex_terms(model))
    throw Error(
        "multigrid: fine_level built does not carry the inertia, obstacle contact or self-contact barrier blocks "
        "(use automatic or current)");
}

// A read-only device copy of `v` as T (at least one entry), its bytes added
// to `bytes`.
template <typename T, typename V>
device::Buffer upload_as(device::OpenClContext& cl, const V& v, size_t& bytes) {
  const std::vector<T> r(v.begin(), v.end());
  bytes += r.size() * sizeof(T);
  return cl.buffer(CL_MEM_READ_ONLY, std::max<size_t>(r.size(), 1) * sizeof(T), r.empty() ? nullptr : r.data());
}

// The coarsest operator's sparsity (3x3 blocks of vertices sharing a cell)
// in `matrix`, analysed by `factor`; where each cell-matrix entry (c, col,
// row) and each DOF's diagonal go among the matrix's values, so that a build
// adds them up in place.
void prepare_coarsest(const LatticeLevel& h, Eigen::SparseMatrix<double>& matrix,
                      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& factor, std::vector<int>& slots,
                      std::vector<int>& diagonal) {
  std::vector<Eigen::Triplet<double>> pattern;
  for (size_t c = 0; c < h.cells.size(); ++c)
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            pattern.emplace_back(3 * h.elements[8 * c + a] + i, 3 * h.elements[8 * c + b] + j, 1.0);
  matrix = Eigen::SparseMatrix<double>(3 * h.vertex_count, 3 * h.vertex_count);
  matrix.setFromTriplets(pattern.begin(), pattern.end());
  matrix.makeCompressed();
  factor.analyzePattern(matrix);
  auto slot = [&](int row, int col) {
    const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[col];
    const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - matrix.innerIndexPtr());
  };
  slots.resize(h.cells.size() * kCellMatrix);
  for (size_t c = 0; c < h.cells.size(); ++c)
    for (int col = 0; col < 24; ++col)
      for (int row = 0; row < 24; ++row)
        slots[kCellMatrix * c + 24 * col + row] =
            slot(3 * h.elements[8 * c + row / 3] + row % 3, 3 * h.elements[8 * c + col / 3] + col % 3);
  diagonal.resize(3 * h.vertex_count);
  for (size_t i = 0; i < 3 * h.vertex_count; ++i) diagonal[i] = slot(static_cast<int>(i), static_cast<int>(i));
}

template <typename Real, typename C>
Levels<Real, C>::Levels(ElasticModel<Real>& model, const Mesh& mesh, const std::vector<char>& mask,
                        const MultigridOptions& options)
    : model_(model),
      cl_(model.context()),
      options_(resolved_smoothing(options, 3 * mesh.vertex_count(), model.max_poisson_ratio())) {
  check_multigrid_options(model, options);
  // Throws for a degree without coefficients.
  chebyshev_steps(*options_.chebyshev_kind, *options_.smoother_degree, 1.0);
  hierarchy_ = build_lattice_hierarchy(mesh, mask, options.coarsest_dofs, options.max_levels);
  build_kernels(mesh, options);
  octant_weights_ = upload_as<Real>(cl_, octant_weights(), table_bytes_);
  if (kNarrow) {  // the fine level's size (a float cycle's is built), the largest
    const size_t bytes = hierarchy_.levels[0].vertex_count * 9 * sizeof(Real);
    wide_inverse_ = cl_.buffer(CL_MEM_READ_WRITE, bytes);
    table_bytes_ += bytes;
  }
  for (size_t l = 0; l < hierarchy_.levels.size(); ++l) levels_.push_back(make_level(l));
  if (hierarchy_.levels.size() > 1)
    prepare_coarsest(hierarchy_.levels.back(), coarsest_matrix_, coarsest_, coarsest_slots_, coarsest_diagonal_);
}

// The kernels every level shares (the coarse levels carry the per-vertex
// terms inside their cell matrices, snh_galerkin_vertex_terms: their
// products, gathers and smoothers are the elastic-only builds), the fine
// level's kind, and each vertex's share of the per-vertex terms.
template <typename Real, typename C>
void Levels<Real, C>::build_kernels(const Mesh& mesh, const MultigridOptions& options) {
  const device::KernelConfig& defines = model_.data().config;
  const device::KernelConfig& coarse = model_.data().elastic_config;
  galerkin_cache_k_ = cl_.kernel("multigrid.cl", coarse, "snh_galerkin_from_cache");
  galerkin_matrices_k_ = cl_.kernel("multigrid.cl", coarse, "snh_galerkin_from_matrices");
  // The V-cycle's builds: a float cycle's are the same switches compiled in
  // float (SNH_FLOAT, kernels/snh_portable.h).
  const device::KernelConfig cycle = cycle_config();
  prolong_k_ = cl_.kernel("multigrid.cl", cycle, "snh_prolong_add");
  if (cl_.info().has_fp64) {
    device::KernelConfig power;
    power.float_cycle = kNarrow;
    power.cg_span = static_cast<int>(kPowerSpan);
    power_dot_k_ = cl_.kernel("cg.cl", power, "snh_cg_dot");
    power_normalize_k_ = cl_.kernel("cg.cl", power, "snh_cg_normalize");
    power_total_k_ = cl_.kernel("reduce.cl", "", "snh_partial_total");
  }
  coarse_on_device_ = options_.coarse_solve_on_device;
  restrict_k_ = cl_.kernel("multigrid.cl", cycle, "snh_restrict");
  chebyshev_start_k_ = cl_.kernel("multigrid.cl", cycle, "snh_chebyshev_start");
  jacobi_setup_k_ = cl_.kernel("fem.cl", coarse, "snh_block_jacobi_setup");
  if constexpr (kNarrow) {
    narrow_k_ = cl_.kernel("fem.cl", coarse, "snh_narrow");
    widen_k_ = cl_.kernel("fem.cl", coarse, "snh_widen");
  }
  vertex_terms_ = has_vertex_terms(model_);
  fine_built_ = builds_fine_level(model_, options);
  if (kNarrow && !fine_built_) throw Error("multigrid: a float V-cycle needs a built fine level");
  fine_float_ = fine_built_ && options.fine_level_float && sizeof(Real) > sizeof(float);
  if (fine_float_)
    fine_float_galerkin_k_ = cl_.kernel("multigrid.cl", coarse.with_matrix_float(), "snh_galerkin_from_matrices");
  if (vertex_terms_) {
    galerkin_vertex_k_ = cl_.kernel("multigrid.cl", defines, "snh_galerkin_vertex_terms");
    // Each vertex's terms shared out equally to the cells around it.
    std::vector<int> around(mesh.vertex_count(), 0);
    for (int32_t v : mesh.elements) ++around[static_cast<size_t>(v)];
    std::vector<Real> share(mesh.vertex_count(), Real(0));
    for (size_t v = 0; v < share.size(); ++v)
      if (around[v] > 0) share[v] = Real(1) / static_cast<Real>(around[v]);
    vertex_share_ = cl_.buffer(CL_MEM_READ_ONLY, share.size() * sizeof(Real), share.data());
    table_bytes_ += share.size() * sizeof(Real);
  }
}

// Level l of the hierarchy on the device: its mask, elements, cell
// matrices with their blocks and assembled stencil (the coarse levels, and
// a built fine level), transfers and vectors.
template <typename Real, typename C>
std::unique_ptr<typename Levels<Real, C>::Level> Levels<Real, C>::make_level(size_t l) {
  const LatticeLevel& h = hierarchy_.levels[l];
  auto level = std::make_unique<Level>();
  Level& L = *level;
  L.cells = h.cells.size();
  L.vertices = h.vertex_count;
  const size_t n = 3 * L.vertices;
  L.mask = upload_as<Real>(cl_, h.mask, L.bytes);
  if (kNarrow) L.cycle_mask = upload_as<C>(cl_, h.mask, L.bytes);
  if (l == 0) {
    L.element_handle = model_.data().elements.get();
  } else {
    L.elements = upload_as<int>(cl_, h.elements, L.bytes);
    L.element_handle = L.elements.get();
    L.children = upload_as<int>(cl_, h.children, L.bytes);
  }
  if (l > 0 || fine_built_) {  // cell matrices, their blocks and the assembled operator
    const fem::VertexSlots slots = fem::vertex_slots(h.elements, L.vertices);
    L.offsets = upload_as<int>(cl_, slots.offsets, L.bytes);
    L.adjacency = upload_as<int>(cl_, slots.adjacency, L.bytes);
    const size_t tile = model_.data().cache_tile;
    const StencilTables stencil = device_stencil_tables(h.elements, L.vertices, 8, slots, tile);
    L.width = stencil.width;
    // Float matrices at a float fine level: assembled from float
    // (SNH_MATRIX_FLOAT), and in a Real cycle read by mixed kernels.
    const bool float_matrices = l == 0 && fine_float_;
    const device::KernelConfig& coarse = model_.data().elastic_config;
    const device::KernelConfig cycle = cycle_config();
    const device::KernelConfig assembly =
        stencil_build(float_matrices ? coarse.with_matrix_float() : coarse, L.width, tile, stencil.lower);
    const device::KernelConfig apply =
        stencil_build(float_matrices && !kNarrow ? cycle.with_matrix_float() : cycle, L.width, tile, stencil.lower);
    L.stencil_kernels = StencilKernels{cl_.kernel("stencil.cl", assembly, "snh_stencil_assemble"),
                                       cl_.kernel("stencil.cl", apply, "snh_stencil_product"),
                                       cl_.kernel("stencil.cl", apply, "snh_stencil_residual"),
                                       cl_.kernel("stencil.cl", apply, "snh_chebyshev_step")};
    L.neighbours = upload_as<int>(cl_, tiled_neighbours(stencil, L.vertices, tile), L.bytes);
    L.part_offsets = upload_as<int>(cl_, stencil.part_offsets, L.bytes);
    L.parts = upload_as<int>(cl_, stencil.parts, L.bytes);
    const size_t entry = l == 0 && fine_float_ ? sizeof(float) : sizeof(Real);
    const size_t stencil_entry = l == 0 && fine_float_ ? sizeof(float) : sizeof(C);
    const size_t matrix_bytes = L.cells * kCellMatrix * entry,
                 stencil_bytes = stencil_entries(stencil, L.vertices, tile) * stencil_entry;
    L.matrices = cl_.buffer(CL_MEM_READ_WRITE, matrix_bytes);
    L.stencil = cl_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(stencil_bytes, 1));
    L.blocks = cl_.buffer(CL_MEM_READ_WRITE, L.cells * 72 * sizeof(Real));
    L.inverse = cl_.buffer(CL_MEM_READ_WRITE, L.vertices * 9 * sizeof(C));
    L.bytes += matrix_bytes + stencil_bytes + L.cells * 72 * sizeof(Real) + L.vertices * 9 * sizeof(C);
  }
  if (l + 1 < hierarchy_.levels.size()) {
    L.prolong_vertices = upload_as<int>(cl_, h.prolongation_vertices, L.bytes);
    L.prolong_weights = upload_as<C>(cl_, h.prolongation_weights, L.bytes);
    L.restrict_offsets = upload_as<int>(cl_, h.restriction_offsets, L.bytes);
    L.restrict_vertices = upload_as<int>(cl_, h.restriction_vertices, L.bytes);
    L.restrict_weights = upload_as<C>(cl_, h.restriction_weights, L.bytes);
  }
  for (auto* v : {&L.b, &L.x, &L.r, &L.d, &L.t, &L.d_next, &L.eigenvector})
    *v = viennacl::vector<C>(viennacl::scalar_vector<C>(n, C(0)));
  L.bytes += 7 * n * sizeof(C);
  return level;
}

template <typename Real, typename C>
void Levels<Real, C>::product(int level, const VectorBase& p, VectorBase& y) const {
  if (level == 0 && !fine_built_) {  // C is Real: a float cycle has a built fine level
    if constexpr (!kNarrow) model_.product(p, y);
    return;
  }
  const Level& L = *levels_[level];
  const int vertices = static_cast<int>(L.vertices);
  cl_kernel k = stencil_kernels(level).product.get();
  KernelArgs args(k);
  args.add(mem(p))
      .add(L.neighbours.get())
      .add(L.stencil.get())
      .add(L.cycle_mask_handle())
      .add(vertices)
      .add(L.width)
      .add(mem(y));
  cl_.run(args.bind(), L.vertices);
}

template <typename Real, typename C>
void Levels<Real, C>::residual(int level, const VectorBase& p, const VectorBase& base, VectorBase& r) const {
  const Level& L = *levels_[level];
  cl_kernel k = stencil_kernels(level).residual.get();
  KernelArgs args(k);
  args.add(mem(p))
      .add(L.neighbours.get())
      .add(L.stencil.get())
      .add(L.cycle_mask_handle())
      .add(static_cast<int>(L.vertices))
      .add(L.width)
      .add(mem(base))
      .add(mem(r));
  cl_.run(args.bind(), L.vertices);
}

template <typename Real, typename C>
void Levels<Real, C>::assemble_stencil(int level) {
  const Level& L = *levels_[level];
  cl_kernel k = stencil_kernels(level).assemble.get();
  const int vertices = static_cast<int>(L.vertices);
  const int blocks = vertices * L.width;
  // The fine level's float matrices give a float stencil (matrix_real); in
  // a float cycle the coarse levels' Real sums are stored narrowed.
  const bool narrowed = kNarrow && !(level == 0 && fine_float_);
  KernelArgs args(k);
  args.add(L.matrices.get())
      .add(L.part_offsets.get())
      .add(L.parts.get())
      .add(blocks)
      .add(L.width)
      .add(narrowed ? cl_mem{nullptr} : L.stencil.get())
      .add(narrowed ? L.stencil.get() : cl_mem{nullptr});
  cl_.run(args.bind(), static_cast<size_t>(blocks));
}

template <typename Real, typename C>
void Levels<Real, C>::inverse_diagonal(int level, VectorBase& z) const {
  if (level == 0 && !fine_built_) {
    if constexpr (!kNarrow) model_.apply_preconditioner(z);
    return;
  }
  // As the smoothing's first step with c = beta = 1 from x = 0 (x = d =
  // D^-1 r; r and x may alias): the V-cycle's own program, so that a float
  // cycle builds no float fem.cl.
  Level& L = *levels_[level];
  cl_kernel k = chebyshev_start_k_.get();
  KernelArgs args(k);
  args.add(L.inverse.get())
      .add(mem(z))
      .add(C(1))
      .add(C(1))
      .add(static_cast<int>(L.vertices))
      .add(0)
      .add(mem(L.d))
      .add(mem(z));
  cl_.run(args.bind(), L.vertices);
}

template <typename Real, typename C>
void Levels<Real, C>::setup() {
  if (fine_built_) {
    Level& L = *levels_[0];
    model_.products().element_matrices_into(L.matrices.get(), L.blocks.get(), fine_float_);
    assemble_stencil(0);
    block_jacobi(L);
  }
  for (size_t l = 1; l < levels_.size(); ++l) {
    Level& L = *levels_[l];
    const Level& F = *levels_[l - 1];
    const int cells = static_cast<int>(L.cells);
    const cl_mem fine_matrices =
        l == 1 && !fine_built_ ? model_.products().element_matrices_buffer() : F.matrices.get();
    if (!fine_matrices) {
      cl_kernel k = galerkin_cache_k_.get();
      KernelArgs args(k);
      args.add(octant_weights_.get())
          .add(L.children.get())
          .add(F.element_handle)
          .add(model_.data().gradients.get())
          .add(model_.data().weights.get())
          .add(model_.data().cache.get())
          .add(F.mask.get())
          .add(cells)
          .add(L.matrices.get())
          .add(L.blocks.get());
      cl_.run(args.bind(), L.cells);
    } else {
      cl_kernel k = l == 1 && fine_float_ ? fine_float_galerkin_k_.get() : galerkin_matrices_k_.get();
      KernelArgs args(k);
      args.add(octant_weights_.get())
          .add(L.children.get())
          .add(F.element_handle)
          .add(fine_matrices)
          .add(F.mask.get())
          .add(cells)
          .add(L.matrices.get())
          .add(L.blocks.get());
      cl_.run(args.bind(), L.cells);
    }
    if (l == 1 && vertex_terms_) {
      cl_kernel k = galerkin_vertex_k_.get();
      KernelArgs args(k);
      args.add(octant_weights_.get())
          .add(L.children.get())
          .add(F.element_handle)
          .add(vertex_share_.get())
          .add(F.mask.get())
          .add(cells)
          .add(static_cast<Real>(model_.elastic_scale()));
      if (model_.inertia_buffer()) args.add(model_.inertia_buffer());
      if (model_.contact().contact_blocks_buffer()) args.add(model_.contact().contact_blocks_buffer());
      if (const auto* barrier = model_.contact().self_barrier()) args.add(barrier->diagonal());
      args.add(L.matrices.get()).add(L.blocks.get());
      cl_.run(args.bind(), L.cells);
    }
    assemble_stencil(static_cast<int>(l));
    block_jacobi(L);
  }
  factor_coarsest();
  // lambda_max(D^-1 A) per smoothed level by power iteration: the first
  // setup from a fixed start (deterministic), later ones warm-started from
  // the last eigenvector estimate, whose operator changed by one Newton step
  // only. Norms are reduced on the device in a fixed order. The coarsest
  // level too where it is smoothed or solved by its own polynomial.
  const size_t smoothed = levels_.size() == 1 || !coarsest_ok_ ? levels_.size() : levels_.size() - 1;
  estimate_bounds(0, smoothed);
}

template <typename Real, typename C>
void Levels<Real, C>::block_jacobi(Level& L) {
  cl_kernel s = jacobi_setup_k_.get();
  const int vertices = static_cast<int>(L.vertices);
  KernelArgs args(s);
  args.add(L.blocks.get())
      .add(L.offsets.get())
      .add(L.adjacency.get())
      .add(L.mask.get())
      .add(vertices)
      .add(kNarrow ? wide_inverse_.get() : L.inverse.get());
  cl_.run(args.bind(), L.vertices);
  if (kNarrow) convert(narrow_k_, wide_inverse_.get(), 9 * L.vertices, L.inverse.get());
}

template <typename Real, typename C>
void Levels<Real, C>::convert(const device::Kernel& k, cl_mem from, size_t values, cl_mem to) const {
  cl_kernel c = k.get();
  KernelArgs args(c);
  args.add(from).add(static_cast<int>(values)).add(to);
  cl_.run(args.bind(), values);
}

template <typename Real, typename C>
void Levels<Real, C>::update_fine_bound() {
  if (fine_built_) return;
  // Barrier self-contact: pairs come within dhat and leave between builds,
  // each with a diagonal block that can outweigh the elastic one by orders
  // of magnitude, so the fine smoother takes this linearization's blocks:
  // fewer Newton and CG iterations than with the build's (docs/performance.md,
  // "Fine smoother with barrier self-contact").
  if (model_.contact().self_barrier()) model_.setup_preconditioner();
  estimate_bounds(0, 1);
}

template <typename Real, typename C>
void Levels<Real, C>::estimate_bounds(size_t first, size_t count) {
  if (count == 0) return;
  if (!power_dot_k_) {
    for (size_t l = first; l < first + count; ++l) estimate_on_host(*levels_[l], l);
    return;
  }
  if (!power_totals_ || device::OpenClContext::bytes(power_totals_.get()) < levels_.size() * sizeof(double))
    power_totals_ = cl_.buffer(CL_MEM_READ_WRITE, levels_.size() * sizeof(double));
  for (size_t l = first; l < first + count; ++l) queue_estimate(*levels_[l], l, static_cast<int>(l - first));
  std::vector<double> totals(count);
  cl_.read(power_totals_.get(), count * sizeof(double), totals.data());
  for (size_t l = first; l < first + count; ++l) set_bound(*levels_[l], std::sqrt(totals[l - first]));
}

template <typename Real, typename C>
void Levels<Real, C>::set_bound(Level& L, double lambda) {
  L.estimated = std::isfinite(lambda) && lambda > 0.0;
  if (!L.estimated) lambda = 1.0;  // start again next time
  L.lambda = lambda;
  L.steps = chebyshev_steps(*options_.chebyshev_kind, *options_.smoother_degree, lambda);
  if (coarse_on_device_ && &L == levels_.back().get())
    L.solve_steps = chebyshev_interval_steps(kCoarseDegree, kUpperBound * lambda / kCoarseSpread, kUpperBound * lambda);
}

// The start: the last estimate's eigenvector, or a fixed pseudo-random
// vector (deterministic) on the level's free DOFs. Returns the steps to run.
template <typename C>
int start_power_iteration(const LatticeLevel& h, bool estimated, viennacl::vector<C>& eigenvector,
                          device::OpenClContext& cl) {
  const bool warm = estimated && eigenvector.size() == 3 * h.vertex_count;
  if (!warm) {
    std::vector<C> start(3 * h.vertex_count);
    uint32_t state = 12345u;
    for (size_t i = 0; i < start.size(); ++i) {
      state = state * 1664525u + 1013904223u;
      start[i] = h.mask[i] ? C(0.5 + static_cast<double>(state >> 8) / 16777216.0) : C(0);
    }
    device::write_to_device(cl, start, eigenvector);
  }
  return warm ? kWarmPowerIterations : kPowerIterations;
}

template <typename Real, typename C>
void Levels<Real, C>::estimate_on_host(Level& L, size_t l) {
  const int iterations = start_power_iteration(hierarchy_.levels[l], L.estimated, L.eigenvector, cl_);
  double lambda = 0.0;
  for (int it = 0; it < iterations; ++it) {
    const double norm = static_cast<double>(viennacl::linalg::norm_2(L.eigenvector));
    if (!(norm > 0.0) || !std::isfinite(norm)) break;
    L.eigenvector *= C(1.0 / norm);
    product(static_cast<int>(l), L.eigenvector, L.t);
    inverse_diagonal(static_cast<int>(l), L.t);
    lambda = static_cast<double>(viennacl::linalg::norm_2(L.t));
    L.eigenvector.fast_swap(L.t);
  }
  set_bound(L, lambda);
}

template <typename Real, typename C>
void Levels<Real, C>::queue_estimate(Level& L, size_t l, int slot) {
  const int iterations = start_power_iteration(hierarchy_.levels[l], L.estimated, L.eigenvector, cl_);
  // Each step normalizes by the norm's partials (kernels/cg.cl) without a
  // read; the final norm's partials are totalled into `slot`.
  const int n = static_cast<int>(3 * L.vertices);
  const size_t groups = (3 * L.vertices + kPowerSpan - 1) / kPowerSpan;
  if (!power_partials_ || device::OpenClContext::bytes(power_partials_.get()) < groups * sizeof(double))
    power_partials_ = cl_.buffer(CL_MEM_READ_WRITE, groups * sizeof(double));
  auto squares = [&](const VectorBase& v) {
    cl_.run(KernelArgs(power_dot_k_.get()).add(mem(v)).add(mem(v)).add(n).add(power_partials_.get()).bind(),
            groups * 64);
  };
  for (int it = 0; it < iterations; ++it) {
    squares(L.eigenvector);
    cl_.run(KernelArgs(power_normalize_k_.get())
                .add(mem(L.eigenvector))
                .add(n)
                .add(power_partials_.get())
                .add(static_cast<int>(groups))
                .bind(),
            groups * 64);
    product(static_cast<int>(l), L.eigenvector, L.t);
    inverse_diagonal(static_cast<int>(l), L.t);
    L.eigenvector.fast_swap(L.t);
  }
  squares(L.eigenvector);
  cl_.run(KernelArgs(power_total_k_.get())
              .add(power_partials_.get())
              .add(0)
              .add(static_cast<int>(groups))
              .add(0)
              .add(power_totals_.get())
              .add(slot)
              .bind(),
          1);
}

template <typename Real, typename C>
void Levels<Real, C>::factor_coarsest() {
  coarsest_ok_ = false;
  if (levels_.size() < 2 || coarse_on_device_) return;
  const Level& L = *levels_.back();
  const LatticeLevel& h = hierarchy_.levels.back();
  std::vector<Real> local(L.cells * kCellMatrix);
  cl_.read(L.matrices.get(), local.size() * sizeof(Real), local.data());
  double* values = coarsest_matrix_.valuePtr();
  std::fill(values, values + coarsest_matrix_.nonZeros(), 0.0);
  for (size_t k = 0; k < local.size(); ++k) values[coarsest_slots_[k]] += static_cast<double>(local[k]);
  for (size_t i = 0; i < 3 * L.vertices; ++i)
    if (!h.mask[i]) values[coarsest_diagonal_[i]] += 1.0;  // dead DOF (its row and column are 0): identity
  coarsest_.factorize(coarsest_matrix_);
  coarsest_ok_ = coarsest_.info() == Eigen::Success && coarsest_.vectorD().minCoeff() > 0.0;
}

template <typename Real, typename C>
void Levels<Real, C>::coarse_solve() const {
  Level& L = *levels_.back();
  if (coarse_on_device_) {
    chebyshev(static_cast<int>(levels_.size()) - 1, L.x, L.r, false, &L.b, &L.solve_steps);
    return;
  }
  if (!coarsest_ok_) {  // a singular coarsest operator: smooth instead
    chebyshev(static_cast<int>(levels_.size()) - 1, L.x, L.r, false, &L.b);
    return;
  }
  device::read_back(cl_, L.b, host_rhs_);
  Eigen::VectorXd rhs(host_rhs_.size());
  for (size_t i = 0; i < host_rhs_.size(); ++i) rhs[i] = static_cast<double>(host_rhs_[i]);
  const Eigen::VectorXd solution = coarsest_.solve(rhs);
  const LatticeLevel& h = hierarchy_.levels.back();
  for (size_t i = 0; i < host_rhs_.size(); ++i) host_rhs_[i] = h.mask[i] ? static_cast<C>(solution[i]) : C(0);
  device::write_to_device(cl_, host_rhs_, L.x);
}

template <typename Real, typename C>
void Levels<Real, C>::chebyshev(int level, VectorBase& x, VectorBase& r, bool want_residual, const VectorBase* from,
                                const ChebyshevSteps* polynomial) const {
  Level& L = *levels_[level];
  const ChebyshevSteps& steps = polynomial ? *polynomial : L.steps;
  const int degree = static_cast<int>(steps.c_z.size());
  // With weights beta != 1 on the updates of x the recurrence's r is not
  // b - A x: the residual asked for is then computed from x and b (`from`).
  const bool weighted = steps.weighted();
  if (weighted && want_residual && !from) throw Error("multigrid: a weighted smoothing's residual needs its b");
  if (level > 0 || fine_built_) {  // one pass per degree (snh_chebyshev_step)
    const int count = static_cast<int>(L.vertices);
    const VectorBase& start = from ? *from : r;  // r's value on entry
    {
      cl_kernel k = chebyshev_start_k_.get();
      const int accumulate = from ? 0 : 1;
      KernelArgs args(k);
      args.add(L.inverse.get())
          .add(mem(start))
          .add(static_cast<C>(steps.c_z[0]))
          .add(static_cast<C>(steps.beta[0]))
          .add(count)
          .add(accumulate)
          .add(mem(L.d))
          .add(mem(x));
      cl_.run(args.bind(), L.vertices);
    }
    for (int i = 1; i < degree; ++i) {
      cl_kernel s = stencil_kernels(level).step.get();
      KernelArgs args(s);
      args.add(mem(L.d))
          .add(L.neighbours.get())
          .add(L.stencil.get())
          .add(L.cycle_mask_handle())
          .add(L.inverse.get())
          .add(count)
          .add(L.width)
          .add(static_cast<C>(steps.c_d[i]))
          .add(static_cast<C>(steps.c_z[i]))
          .add(static_cast<C>(steps.beta[i]))
          .add(mem(i == 1 ? start : r))
          .add(mem(r))
          .add(mem(x))
          .add(mem(L.d_next));
      cl_.run(args.bind(), L.vertices);
      L.d.fast_swap(L.d_next);
    }
    if (want_residual) {
      if (weighted)
        residual(level, x, start, r);
      else
        residual(level, L.d, degree == 1 ? start : r, r);
    }
    return;
  }
  if (from) {
    x.clear();
    r = *from;
  }
  L.d = r;
  inverse_diagonal(level, L.d);
  L.d *= C(steps.c_z[0]);
  for (int i = 1; i <= degree; ++i) {
    x += C(steps.beta[i - 1]) * L.d;
    if (i == degree && !want_residual) break;
    if (i == degree && weighted) {
      product(level, x, L.t);
      r = *from - L.t;
      break;
    }
    product(level, L.d, L.t);
    r -= L.t;
    if (i == degree) break;
    L.t = r;
    inverse_diagonal(level, L.t);
    L.d = C(steps.c_d[i]) * L.d + C(steps.c_z[i]) * L.t;
  }
}

template <typename Real, typename C>
void Levels<Real, C>::vcycle(int level) const {
  Level& L = *levels_[level];
  if (level + 1 == static_cast<int>(levels_.size())) {
    if (level == 0) {  // a single level: one symmetric Chebyshev smoothing
      chebyshev(0, L.x, L.r, false, &L.b);
    } else {
      coarse_solve();
    }
    return;
  }
  Level& K = *levels_[level + 1];
  chebyshev(level, L.x, L.r, true, &L.b);
  {
    cl_kernel k = restrict_k_.get();
    const int count = static_cast<int>(K.vertices);
    KernelArgs args(k);
    args.add(mem(L.r))
        .add(L.cycle_mask_handle())
        .add(L.restrict_offsets.get())
        .add(L.restrict_vertices.get())
        .add(L.restrict_weights.get())
        .add(K.cycle_mask_handle())
        .add(count)
        .add(mem(K.b));
    cl_.run(args.bind(), K.vertices);
  }
  vcycle(level + 1);
  {
    cl_kernel k = prolong_k_.get();
    const int count = static_cast<int>(L.vertices);
    KernelArgs args(k);
    args.add(mem(K.x))
        .add(L.prolong_vertices.get())
        .add(L.prolong_weights.get())
        .add(L.cycle_mask_handle())
        .add(count)
        .add(mem(L.x));
    cl_.run(args.bind(), L.vertices);
  }
  if (level > 0 || fine_built_) {
    residual(level, L.x, L.b, L.r);
  } else {
    product(level, L.x, L.t);
    L.r = L.b - L.t;
  }
  chebyshev(level, L.x, L.r, false);
}

template <typename Real, typename C>
void Levels<Real, C>::apply(WideBase& z) const {
  Level& fine = *levels_[0];
  if constexpr (kNarrow) {
    convert(narrow_k_, mem(z), z.size(), mem(fine.b));
    vcycle(0);
    convert(widen_k_, mem(fine.x), z.size(), mem(z));
  } else {
    cl_.copy(mem(z), mem(fine.b), z.size() * sizeof(C));
    vcycle(0);
    cl_.copy(mem(fine.x), mem(z), z.size() * sizeof(C));
  }
}

template <typename Real, typename C>
void Levels<Real, C>::level_product(int level, const WideBase& p, WideBase& y) const {
  if constexpr (kNarrow) {
    viennacl::vector<C> narrow_p(p.size()), narrow_y(p.size());
    convert(narrow_k_, mem(p), p.size(), mem(narrow_p));
    product(level, narrow_p, narrow_y);
    convert(widen_k_, mem(narrow_y), p.size(), mem(y));
  } else {
    product(level, p, y);
  }
}

template <typename Real, typename C>
std::vector<Real> Levels<Real, C>::level_matrices(int level) const {
  if (level < (fine_built_ ? 0 : 1) || level >= levels())
    throw Error("multigrid: no matrices at level " + std::to_string(level));
  const Level& L = *levels_[level];
  if (level == 0 && fine_float_) {
    std::vector<float> narrow(L.cells * kCellMatrix);
    cl_.read(L.matrices.get(), narrow.size() * sizeof(float), narrow.data());
    return std::vector<Real>(narrow.begin(), narrow.end());
  }
  std::vector<Real> out(L.cells * kCellMatrix);
  cl_.read(L.matrices.get(), out.size() * sizeof(Real), out.data());
  return out;
}

template <typename Real, typename C>
std::vector<double> Levels<Real, C>::eigenvalue_estimates() const {
  std::vector<double> out;
  for (const auto& L : levels_) out.push_back(L->lambda);
  return out;
}

template <typename Real, typename C>
size_t Levels<Real, C>::memory_bytes() const {
  size_t bytes = table_bytes_;
  for (const auto& L : levels_) bytes += L->bytes;
  return bytes;
}

}  // namespace

template <typename Real>
MultigridPreconditioner<Real>::MultigridPreconditioner(ElasticModel<Real>& model, const Mesh& mesh,
                                                       const std::vector<char>& mask, const MultigridOptions& options) {
  if constexpr (sizeof(Real) > sizeof(float)) {
    if (options.float_cycle && builds_fine_level(model, options)) {
      cycle_ = std::make_unique<Levels<Real, float>>(model, mesh, mask, options);
      return;
    }
  }
  cycle_ = std::make_unique<Levels<Real, Real>>(model, mesh, mask, options);
}

template <typename Real>
MultigridPreconditioner<Real>::~MultigridPreconditioner() = default;

template <typename Real>
void MultigridPreconditioner<Real>::setup() {
  cycle_->setup();
}
template <typename Real>
void MultigridPreconditioner<Real>::update_fine_bound() {
  cycle_->update_fine_bound();
}
template <typename Real>
void MultigridPreconditioner<Real>::forget_estimates() {
  cycle_->forget_estimates();
}
template <typename Real>
bool MultigridPreconditioner<Real>::fine_level_built() const {
  return cycle_->fine_level_built();
}
template <typename Real>
bool MultigridPreconditioner<Real>::float_cycle() const {
  return cycle_->float_cycle();
}
template <typename Real>
void MultigridPreconditioner<Real>::apply(VectorBase& z) const {
  cycle_->apply(z);
}
template <typename Real>
const LatticeHierarchy& MultigridPreconditioner<Real>::hierarchy() const {
  return cycle_->hierarchy();
}
template <typename Real>
const MultigridOptions& MultigridPreconditioner<Real>::options() const {
  return cycle_->options();
}
template <typename Real>
int MultigridPreconditioner<Real>::levels() const {
  return cycle_->levels();
}
template <typename Real>
std::vector<Real> MultigridPreconditioner<Real>::level_matrices(int level) const {
  return cycle_->level_matrices(level);
}
template <typename Real>
void MultigridPreconditioner<Real>::level_product(int level, const VectorBase& p, VectorBase& y) const {
  cycle_->level_product(level, p, y);
}
template <typename Real>
std::vector<double> MultigridPreconditioner<Real>::eigenvalue_estimates() const {
  return cycle_->eigenvalue_estimates();
}
template <typename Real>
size_t MultigridPreconditioner<Real>::memory_bytes() const {
  return cycle_->memory_bytes();
}

template class MultigridPreconditioner<float>;
template class MultigridPreconditioner<double>;

}  // namespace snh::solver
