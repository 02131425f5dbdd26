#include "throughput.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "device/kernel_args.h"
#include "device/kernel_source.h"
#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "enum_names.h"
#include "fem/rest_state.h"
#include "host_baseline.h"
#include "record_writer.h"
#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/simulation.h"
#include "solver/model/elastic_model.h"
#include "timing.h"

namespace snh::bench {

// bench/roofline.cl, embedded in the benchmark, not the library
// (cmake/embed_text.cmake).
extern const char* const kRooflineSource;

namespace {

using json = nlohmann::ordered_json;

struct Roofline {
  double bandwidth = 0.0;  // bytes per second, triad: the faster of the two forms
  double bandwidth_scalar = 0.0;
  double bandwidth_vector = 0.0;  // 4 entries per work-item
  double peak_scalar = 0.0;       // flops per second
  double peak_vector = 0.0;
  // 8-wide square roots and divisions per second (each lane one), alone and
  // half and half (roofline.cl: whether the two share a unit).
  double sqrt_rate = 0.0, div_rate = 0.0, sqrt_div_rate = 0.0;
  double peak() const { return std::max(peak_scalar, peak_vector); }
};

// roofline.cl's programs, built as OpenClContext::program builds the
// library's (the working precision, SNH_GPU), with its #include of
// snh_portable.h taken from the library's kernels; one per build
// (device::KernelConfig: only fma_chains varies).
class RooflineKernels {
 public:
  explicit RooflineKernels(device::OpenClContext& cl) : cl_(cl) {}

  device::Kernel kernel(const device::KernelConfig& config, const char* name) {
    device::Program& program = programs_[config.cache_key("roofline.cl")];
    if (!program) program = build(config);
    cl_int status = CL_SUCCESS;
    device::Kernel k(clCreateKernel(program.get(), name, &status));
    device::check(status, "clCreateKernel");
    return k;
  }

 private:
  device::Program build(const device::KernelConfig& config) const {
    std::string source;
    std::istringstream in(kRooflineSource);
    for (std::string line; std::getline(in, line);)
      source += line == "#include \"snh_portable.h\"" ? device::kernel_program_source("snh_portable.h") : line + '\n';
    const char* text = source.c_str();
    const size_t length = source.size();
    cl_int status = CL_SUCCESS;
    device::Program program(clCreateProgramWithSource(cl_.context(), 1, &text, &length, &status));
    device::check(status, "clCreateProgramWithSource");
    const std::string flags = cl_.build_options(config);
    cl_device_id device = cl_.device();
    status = clBuildProgram(program.get(), 1, &device, flags.c_str(), nullptr, nullptr);
    if (status != CL_SUCCESS) {
      size_t size = 0;
      clGetProgramBuildInfo(program.get(), device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
      std::string log(size, '\0');
      clGetProgramBuildInfo(program.get(), device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
      throw Error("OpenCL: building bench/roofline.cl (" + flags + ") failed with error " + std::to_string(status) +
                  "; build log:\n" + log);
    }
    return program;
  }

  device::OpenClContext& cl_;
  std::map<std::string, device::Program> programs_;
};

template <typename Real>
Roofline measure_roofline(device::OpenClContext& cl, double min_seconds) {
  RooflineKernels roofline(cl);
  // The best time of one launch and the wait for it (launches are queued).
  auto kernel_seconds = [&](cl_kernel k, size_t items) {
    return best_seconds(
        [&] {
          cl.run(k, items);
          cl.finish();
        },
        min_seconds);
  };
  Roofline r;
  // 3 x 256 MiB in either precision: far beyond any cache, and long enough
  // (about 0.25 ms at 3 TB/s) that a GPU's launch latency stays a few percent
  // (at 3 x 32 MiB of float an H100 read 1.1 TB/s, double 3 x 64 MiB 2.2).
  const int n = static_cast<int>((size_t(256) << 20) / sizeof(Real));
  std::vector<Real> init(n, Real(1));
  device::Buffer a = cl.buffer(CL_MEM_READ_WRITE, n * sizeof(Real)),
                 b = cl.buffer(CL_MEM_READ_WRITE, n * sizeof(Real), init.data()),
                 c = cl.buffer(CL_MEM_READ_WRITE, n * sizeof(Real), init.data());
  // The scalar triad over n entries, then the 4-wide one over n / 4 vectors.
  auto triad_seconds = [&](const char* name, int items) {
    device::Kernel triad = roofline.kernel({}, name);
    return kernel_seconds(
        device::KernelArgs(triad.get()).add(a.get()).add(b.get()).add(c.get()).add(Real(0.5)).add(items).bind(),
        static_cast<size_t>(items));
  };
  r.bandwidth_scalar = 3.0 * n * sizeof(Real) / triad_seconds("snh_triad", n);
  r.bandwidth_vector = 3.0 * n * sizeof(Real) / triad_seconds("snh_triad4", n / 4);
  r.bandwidth = std::max(r.bandwidth_scalar, r.bandwidth_vector);

  const int items = 1 << 16;
  device::Buffer out = cl.buffer(CL_MEM_READ_WRITE, items * sizeof(Real));
  const Real m = Real(0.999), k = Real(0.001);
  // {kernel, its build's chains (0: roofline.cl's 8), chains, lanes}; the
  // 8-wide peak is the faster of 8 and 6 chains (roofline.cl, SNH_FMA_CHAINS).
  struct Fma {
    const char* name;
    int build_chains, chains, lanes;
  };
  for (const Fma& f :
       {Fma{"snh_fma_scalar", 0, 8, 1}, Fma{"snh_fma_vector", 0, 8, 8}, Fma{"snh_fma_vector", 6, 6, 8}}) {
    device::KernelConfig config;
    config.fma_chains = f.build_chains;
    device::Kernel fma = roofline.kernel(config, f.name);
    const double t = kernel_seconds(device::KernelArgs(fma.get()).add(out.get()).add(m).add(k).bind(), items);
    const double flops = 2.0 * f.chains * 256 * items * f.lanes;  // SNH_FMA_ITERATIONS = 256
    double& peak = f.lanes == 1 ? r.peak_scalar : r.peak_vector;
    peak = std::max(peak, flops / t);
  }
  const int slow_items = 1 << 13;
  struct Slow {
    const char* name;
    double* rate;
  };
  for (const Slow& op : {Slow{"snh_sqrt_vector", &r.sqrt_rate}, Slow{"snh_div_vector", &r.div_rate},
                         Slow{"snh_sqrt_div_vector", &r.sqrt_div_rate}}) {
    device::Kernel slow = roofline.kernel({}, op.name);
    const double t = kernel_seconds(device::KernelArgs(slow.get()).add(out.get()).add(m).bind(), slow_items);
    *op.rate = 64.0 * 32 * slow_items / t;  // SNH_SLOW_ITERATIONS = 32
  }
  return r;
}

// Operation counts per element, counted from kernels/ (see the comment at
// each): flops of the arithmetic as written, bytes of global memory each
// element's work-item reads and writes with no reuse between elements.
struct Counts {
  double flops = 0.0;
  double bytes = 0.0;
  double sqrts = 0.0, divisions = 0.0;  // of the per-point SVD and eigensystem (recompute)
};

// The assembled variant's block stencil (ProductVariants::assembled_blocks):
// blocks stored, blocks read per product, neighbour-table ints read.
struct StencilShape {
  double stored = 0.0, reads = 0.0, indices = 0.0;
};

// principal_hessian_action: U^T dF and (.) V (2 x 45), the block (15), three
// twist/flip pairs (3 x 8), U (.) and (.) V^T (2 x 45).
constexpr double kActionFlops = 219;
// snh_principal_hessian + principal_hessian_project: the SVD's 5 Jacobi
// sweeps, the material's block and pairs, eigen_sym3 with its Newton steps
// on the cubic, the projected block rebuilt. Counted in pocl's compiled
// SNH linearization (the hex8 lanes program, objdump of its cached object,
// three copies of the body): 1,595 multiplies, adds and subtracts per point
// in double (vmulpd, vaddpd, vsubpd on zmm registers: 4,785 / 3), less F's
// 144; selects and the FP contraction that the kernels do not use are not
// counted. (Earlier a hand count of 576, from the data-dependent
// SVD and the acos/cos eigensolver since replaced; then 1,331
// until the closed-form Jacobi rotations of math/svd3.h, which take 8 more
// multiplies and adds each and fewer square roots and divisions.)
constexpr double kLinearizationFlops = 1451;
// Square roots and divisions per point of the same kernel (vsqrtpd and
// vdivpd per lane; float has one Newton step of the cubic less): Jacobi
// and Givens rotations, eigenvector normalizations, the cubic's steps.
// Before the closed-form rotations: 53 and 71 (float 70).
constexpr double kSqrtPerPoint = 38;
double divisions_per_point(int real_bytes) { return real_bytes == 8 ? 41 : 40; }

// stencil_blocks: the assembled operator's stored 3x3 blocks (vertices x
// width); the kernel reads all of them, p three times per block (counted
// once: neighbours' values stay in cache), the mask, and writes y.
// stored_bytes: of each cached linearization and rest-state value (the
// working precision's, or 4 for a double model's float products).
Counts product_counts(ProductVariant v, int nodes, int quadrature, bool uniform, int real_bytes,
                      const StencilShape& stencil, double elements, double vertices, int stored_bytes) {
  const double dofs = 3.0 * nodes, per_vertex = vertices / elements;
  // Shared: gather p (3N reals, N ints), write 3N reals; the vertex gather
  // reads them back with N adjacency ints and writes 3 reals per vertex.
  Counts c;
  const double rest_bytes = uniform ? 0.0 : quadrature * (dofs + 1) * stored_bytes;
  const double io = 2 * dofs * real_bytes + nodes * 4 + dofs * real_bytes + nodes * 4 + 3 * per_vertex * real_bytes;
  // F (18 N) and scatter (21 N) per point; the gather's 3 N additions.
  const double kinematics = quadrature * 39.0 * nodes + 3.0 * nodes;
  switch (v) {
    case ProductVariant::cached:
      c.flops = kinematics + quadrature * kActionFlops;
      c.bytes = io + rest_bytes + quadrature * 30.0 * stored_bytes;
      break;
    case ProductVariant::recompute:
      c.flops = kinematics + quadrature * (kActionFlops + kLinearizationFlops + 18.0 * nodes);
      c.bytes = io + rest_bytes + dofs * real_bytes;
      c.sqrts = quadrature * kSqrtPerPoint;
      c.divisions = quadrature * divisions_per_point(real_bytes);
      break;
    case ProductVariant::element_matrices:
      c.flops = 2.0 * dofs * dofs + 3.0 * nodes;
      c.bytes = io + dofs * dofs * real_bytes;
      break;
    default:  // assembled block stencil (kernels/fem/block_stencil.h): every stored block once, padding
              // included, each read block's neighbour index (and in the upper layout its mirrored block's
              // index; the mirrored blocks themselves come from the caches), p, y and the mask
      c.flops = 18.0 * stencil.reads / elements;
      c.bytes = (stencil.stored * 9.0 * real_bytes + stencil.indices * 4.0 + 3 * 3 * vertices * real_bytes) / elements;
      break;
  }
  return c;
}

// The host's Eigen CSR product: 2 flops and a value and a column index per
// nonzero, the row offsets, x read and y written once.
Counts csr_counts(double nonzeros, double elements, double vertices) {
  Counts c;
  c.flops = 2.0 * nonzeros / elements;
  c.bytes =
      (nonzeros * (sizeof(double) + 4.0) + (vertices * 3 + 1) * 4.0 + 2 * 3 * vertices * sizeof(double)) / elements;
  return c;
}

Mesh make_mesh(const std::string& type, int n) {
  return cli::element_type_named(type) == ElementType::hex8 ? make_box_lattice(n, n, n, 1.0 / n)
                                                            : make_tet_box(n, n, n, 1.0 / n);
}

// A deformed state with varied, some indefinite, element Hessians.
std::vector<double> deformed(const Mesh& mesh, int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.1 / n, 0.1 / n);
  std::vector<double> x = mesh.positions.xyz();
  for (size_t i = 0; i < x.size(); ++i) x[i] = (i % 3 == 2 ? 1.3 : 0.9) * x[i] + u(rng);
  return x;
}

struct VariantRow {
  std::string element_type, precision, variant;
  int size;
  size_t elements, dofs;
  double product_seconds, setup_seconds, assembly_seconds;
  size_t memory_bytes;
  Counts counts;
  int material_lanes;  // of the linearization and recompute product; 0: the scalar kernels
};

struct OperationRow {
  std::string element_type, precision, operation;
  int size;
  size_t elements;
  double seconds;
};

template <typename Real>
void run_precision(const ThroughputOptions& o, Precision precision, json& report, std::vector<VariantRow>& rows,
                   std::vector<OperationRow>& ops, std::map<std::string, Roofline>& rooflines) {
  device::OpenClContext cl(DeviceOptions{o.device}, precision);
  device::bind_viennacl(cl);
  const std::string pname = to_string(precision);
  std::cerr << "  roofline (" << pname << ")\n";
  const Roofline roof = measure_roofline<Real>(cl, o.min_seconds);
  rooflines[pname] = roof;
  report["device"] = cl.info().platform + " / " + cl.info().name;
  report["device_is_gpu"] = cl.info().is_gpu;
  report["roofline"][pname] = {
      {"triad_bandwidth_gb_s", roof.bandwidth / 1e9},      {"triad_scalar_gb_s", roof.bandwidth_scalar / 1e9},
      {"triad_vector4_gb_s", roof.bandwidth_vector / 1e9}, {"fma_peak_scalar_gflop_s", roof.peak_scalar / 1e9},
      {"fma_peak_vector_gflop_s", roof.peak_vector / 1e9}, {"sqrt_vector_gop_s", roof.sqrt_rate / 1e9},
      {"div_vector_gop_s", roof.div_rate / 1e9},           {"sqrt_div_vector_gop_s", roof.sqrt_div_rate / 1e9}};
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  for (const std::string& type : o.element_types)
    for (int n : o.sizes) {
      const Mesh mesh = make_mesh(type, n);
      const fem::RestState rest = fem::compute_rest_state(mesh);
      const std::vector<double> xh = deformed(mesh, n);
      std::vector<Real> xr(xh.begin(), xh.end());
      viennacl::vector<Real> x(xr.size()), r(xr.size()), p(xr.size()), y(xr.size());
      viennacl::copy(xr.begin(), xr.end(), x.begin());
      std::vector<Real> ph(xr.size());
      std::mt19937_64 rng(3);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      for (Real& v : ph) v = Real(u(rng));
      viennacl::copy(ph.begin(), ph.end(), p.begin());
      solver::ElasticModel<Real> model(cl, mesh, rest, uniform_material(mesh, material), ProductVariant::cached);
      if (o.material_lanes != 0) {
        if (!model.lanes().point_lanes())
          throw Error("throughput: --material-lanes needs the lanes program (CPU devices); " + cl.info().name +
                      " runs the scalar kernels");
        model.lanes().set_material_lanes(o.material_lanes);
      }
      std::cerr << "  " << type << " " << n << "^3 (" << mesh.element_count() << " elements, " << pname << ")\n";
      const size_t ne = mesh.element_count();
      // The model's operations wait for their kernels (each is a phase scope,
      // device/phase_profile.h), so they are timed as they are.
      ops.push_back({type, pname, "residual", n, ne, best_seconds([&] { model.residual(x, r); }, o.min_seconds)});
      ops.push_back({type, pname, "energy", n, ne, best_seconds([&] { model.energy(x); }, o.min_seconds)});
      ops.push_back({type, pname, "linearize", n, ne, best_seconds([&] { model.linearize(x); }, o.min_seconds)});
      for (const std::string& vname : o.variants) {
        // cached-float-products: a double solve's default product
        // (SolveOptions::product_precision), the cached one in float with
        // double p and y; a float model's cached product is already that.
        const bool float_products = vname == kCachedFloatProducts;
        if (float_products && precision != Precision::double_) continue;
        const ProductVariant v = float_products ? ProductVariant::cached : parse_product_variant(vname);
        model.products().set_variant(v);
        model.products().set_float_products(float_products);
        const double setup = best_seconds([&] { model.linearize(x); }, o.min_seconds);
        const double product = best_seconds([&] { model.product(p, y); }, o.min_seconds);
        const double nv = static_cast<double>(mesh.vertex_count()), width = model.products().assembled_width(),
                     lower = model.products().assembled_lower();
        const StencilShape stencil{static_cast<double>(model.products().assembled_blocks()), nv * (width + lower),
                                   nv * (width + 2 * lower)};
        const Counts counts =
            product_counts(v, rest.nodes, rest.quadrature, rest.uniform, sizeof(Real), stencil, static_cast<double>(ne),
                           nv, float_products ? sizeof(float) : sizeof(Real));
        rows.push_back({type, pname, vname, n, ne, xh.size(), product, setup, model.products().last_assembly_seconds(),
                        model.products().variant_memory_bytes(), counts, model.lanes().material_lanes()});
      }
      if (o.host_baseline && precision == Precision::double_) {
        const HostProductTiming host = time_host_product(mesh, material, xh, 20);
        rows.push_back({type, "double", "host-eigen-csr", n, ne, xh.size(), host.product_seconds, host.assembly_seconds,
                        host.assembly_seconds, host.nonzeros * 12 + (xh.size() + 1) * 4,
                        csr_counts(static_cast<double>(host.nonzeros), static_cast<double>(ne),
                                   static_cast<double>(mesh.vertex_count())),
                        0});
      }
    }
}

// The fraction of the FMA peak a kernel with these counts can reach at
// most: its flops at the peak against its square roots and divisions at
// their own measured rates, one after the other (one shared unit, as on
// x86 CPUs: roofline.cl's half-and-half chains measure whether it is).
double peak_ceiling(const Counts& c, const Roofline& roof) {
  const double flop_seconds = c.flops / roof.peak();
  const double slow_seconds = c.sqrts / roof.sqrt_rate + c.divisions / roof.div_rate;
  return flop_seconds / std::max(flop_seconds, slow_seconds);
}

}  // namespace

int run_throughput(const ThroughputOptions& o) {
  json report;
  std::vector<VariantRow> rows;
  std::vector<OperationRow> ops;
  std::map<std::string, Roofline> rooflines;
  for (const std::string& p : o.precisions) {
    const Precision precision = parse_precision(p);
    try {
      if (precision == Precision::double_)
        run_precision<double>(o, precision, report, rows, ops, rooflines);
      else
        run_precision<float>(o, precision, report, rows, ops, rooflines);
    } catch (const Error& e) {
      std::cerr << "snh-gpu-bench throughput: skipped " << p << ": " << e.what() << '\n';
      report["skipped"].push_back(p + ": " + e.what());
    }
  }
  std::filesystem::create_directories(o.out);
  report["counting"] =
      "flops and bytes per element counted from kernels/ as written (bench/throughput.cpp, product_counts): "
      "no reuse of gathered vertex data between elements is assumed; the per-point linearization's multiplies, "
      "adds, square roots and divisions counted in pocl's compiled kernel; peak_ceiling: the fraction of the FMA "
      "peak reachable with the kernel's square roots and divisions at their measured 8-wide rates, one after the "
      "other";
  Table csv;
  csv.columns = {"element_type",
                 "precision",
                 "size",
                 "elements",
                 "dofs",
                 "variant",
                 "product_seconds",
                 "elements_per_second",
                 "setup_seconds",
                 "assembly_seconds",
                 "memory_bytes",
                 "flops_per_element",
                 "bytes_per_element",
                 "fraction_of_peak",
                 "fraction_of_bandwidth",
                 "sqrts_per_element",
                 "divisions_per_element",
                 "peak_ceiling"};
  Table variants;
  variants.columns = {"element",   "precision", "cells",     "variant", "product ms",  "Melem/s",       "setup ms",
                      "memory MB", "flop/elem", "byte/elem", "% peak",  "% bandwidth", "% peak ceiling"};
  std::cout << std::left << std::setw(6) << "elem" << std::setw(8) << "prec" << std::setw(7) << "cells" << std::setw(23)
            << "variant" << std::setw(12) << "product ms" << std::setw(10) << "Melem/s" << std::setw(11) << "setup ms"
            << std::setw(11) << "memory MB" << std::setw(8) << "%peak"
            << "%bw\n";
  for (const VariantRow& r : rows) {
    const double rate = static_cast<double>(r.elements) / r.product_seconds;
    const Roofline& roof = rooflines[r.precision];
    const double fpeak = r.counts.flops * rate / roof.peak();
    const double fbw = r.counts.bytes * rate / roof.bandwidth;
    const bool slow_ops = r.counts.sqrts > 0.0 || r.counts.divisions > 0.0;
    const double ceiling = peak_ceiling(r.counts, roof);
    csv.add_row({r.element_type, r.precision, std::to_string(r.size), std::to_string(r.elements),
                 std::to_string(r.dofs), r.variant, number(r.product_seconds, 6), number(rate, 6),
                 number(r.setup_seconds, 6), number(r.assembly_seconds, 6), std::to_string(r.memory_bytes),
                 number(r.counts.flops, 6), number(r.counts.bytes, 6), number(fpeak, 6), number(fbw, 6),
                 number(r.counts.sqrts, 6), number(r.counts.divisions, 6), number(ceiling, 6)});
    report["products"].push_back({{"element_type", r.element_type},
                                  {"precision", r.precision},
                                  {"cells_per_side", r.size},
                                  {"elements", r.elements},
                                  {"dofs", r.dofs},
                                  {"variant", r.variant},
                                  {"product_seconds", r.product_seconds},
                                  {"elements_per_second", rate},
                                  {"setup_seconds", r.setup_seconds},
                                  {"assembly_seconds", r.assembly_seconds},
                                  {"memory_bytes", r.memory_bytes},
                                  {"flops_per_element", r.counts.flops},
                                  {"bytes_per_element", r.counts.bytes},
                                  {"fraction_of_peak", fpeak},
                                  {"fraction_of_bandwidth", fbw},
                                  {"sqrts_per_element", r.counts.sqrts},
                                  {"divisions_per_element", r.counts.divisions},
                                  {"peak_ceiling", ceiling},
                                  {"material_lanes", r.material_lanes}});
    variants.add_row({r.element_type, r.precision, std::to_string(r.size) + "^3", r.variant,
                      number(1e3 * r.product_seconds, 3), number(rate / 1e6, 3), number(1e3 * r.setup_seconds, 3),
                      number(static_cast<double>(r.memory_bytes) / 1e6, 3), number(r.counts.flops, 4),
                      number(r.counts.bytes, 4), number(100 * fpeak, 3), number(100 * fbw, 3),
                      slow_ops ? number(100 * ceiling, 3) : ""});
    std::cout << std::left << std::setw(6) << r.element_type << std::setw(8) << r.precision << std::setw(7)
              << (std::to_string(r.size) + "^3") << std::setw(23) << r.variant << std::setw(12)
              << number(1e3 * r.product_seconds, 3) << std::setw(10) << number(rate / 1e6, 3) << std::setw(11)
              << number(1e3 * r.setup_seconds, 3) << std::setw(11)
              << number(static_cast<double>(r.memory_bytes) / 1e6, 3) << std::setw(8) << number(100 * fpeak, 3)
              << number(100 * fbw, 3) << '\n';
  }
  // The winner per element type and precision: the least time per Newton
  // iteration for a typical 50 products per setup.
  std::map<std::string, std::pair<double, std::string>> winners;
  for (const VariantRow& r : rows) {
    if (r.variant == "host-eigen-csr") continue;
    const std::string key = r.element_type + " " + r.precision + " " + std::to_string(r.size);
    const double cost = r.setup_seconds + 50.0 * r.product_seconds;
    auto it = winners.find(key);
    if (it == winners.end() || cost < it->second.first) winners[key] = {cost, r.variant};
  }
  std::ostringstream md;
  md << markdown_text(variants) << "\nWinner (setup + 50 products per Newton iteration):\n\n";
  for (const auto& [key, w] : winners) {
    md << "- " << key << "^3: " << w.second << '\n';
    report["winners"][key] = w.second;
    std::cout << "winner " << key << "^3: " << w.second << '\n';
  }
  Table operations;
  operations.columns = {"element", "precision", "cells", "operation", "ms", "Melem/s"};
  for (const OperationRow& r : ops) {
    operations.add_row({r.element_type, r.precision, std::to_string(r.size) + "^3", r.operation,
                        number(1e3 * r.seconds, 3), number(static_cast<double>(r.elements) / r.seconds / 1e6, 3)});
    report["operations"].push_back({{"element_type", r.element_type},
                                    {"precision", r.precision},
                                    {"cells_per_side", r.size},
                                    {"operation", r.operation},
                                    {"seconds", r.seconds},
                                    {"elements_per_second", static_cast<double>(r.elements) / r.seconds}});
  }
  md << '\n' << markdown_text(operations);
  Table roof_table;
  roof_table.columns = {"precision",         "triad GB/s",         "scalar triad GB/s",
                        "4-wide triad GB/s", "FMA scalar GFLOP/s", "FMA 8-wide GFLOP/s",
                        "sqrt 8-wide G/s",   "div 8-wide G/s",     "sqrt+div 8-wide G/s"};
  for (const auto& [p, r] : rooflines)
    roof_table.add_row({p, number(r.bandwidth / 1e9, 4), number(r.bandwidth_scalar / 1e9, 4),
                        number(r.bandwidth_vector / 1e9, 4), number(r.peak_scalar / 1e9, 4),
                        number(r.peak_vector / 1e9, 4), number(r.sqrt_rate / 1e9, 4), number(r.div_rate / 1e9, 4),
                        number(r.sqrt_div_rate / 1e9, 4)});
  write_text(o.out + "/throughput.csv", csv_text(csv));
  write_json(o.out + "/throughput.json", report);
  write_text(o.out + "/throughput.md", "# Throughput\n\nDevice: " + report.value("device", std::string("?")) + "\n\n" +
                                           markdown_text(roof_table) + '\n' + md.str());
  std::cout << "wrote " << o.out << "/throughput.{json,csv,md}\n";
  return rows.empty() ? 1 : 0;
}

void add_throughput_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ThroughputOptions>();
  CLI::App* cmd = app.add_subcommand(
      "throughput",
      "Device roofline (triad bandwidth, FMA peak) and the engine's kernels against it: every Hessian-product "
      "variant side by side, residual, energy, linearization, and the host Eigen CSR product");
  cmd->add_option("--element", o->element_types, "element types: hex8, tet4")
      ->check(CLI::IsMember(cli::element_type_names()))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--precision", o->precisions, "float, double")
      ->check(CLI::IsMember(cli::precision_names()))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--size", o->sizes, "cells per side of the box lattice (comma list)")
      ->delimiter(',')
      ->check(CLI::Range(1, 200))
      ->capture_default_str();
  cmd->add_option("--variant", o->variants,
                  "product variants: recompute, cached, cached-float-products (double only: the cached product in "
                  "float with double vectors, a double solve's default), element-matrices, assembled")
      ->check(CLI::IsMember({"recompute", "cached", kCachedFloatProducts, "element-matrices", "assembled"}))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--min-seconds", o->min_seconds, "minimum time spent timing each operation")->capture_default_str();
  cmd->add_flag("!--no-host-baseline", o->host_baseline, "skip the host Eigen CSR product");
  cmd->add_option("--material-lanes", o->material_lanes,
                  "CPU devices: lanes of the linearization and recompute product, 8 or 16 (default: 16 where the "
                  "device's native vectors hold 8 values of the precision, else 8)")
      ->check(CLI::IsMember({8, 16}));
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = run_throughput(*o); });
}

}  // namespace snh::bench
