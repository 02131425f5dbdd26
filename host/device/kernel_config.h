// What a kernel program is built with, as typed fields: element type,
// material specialization, per-point data layout, the per-vertex terms a
// scene compiles in and the variant switches of single programs (lanes,
// float copies, stencil widths). One table (kernel_config.cpp) names the
// build switch (-DSNH_*) of each field, in the order they are written, and
// serves both directions: render (the compile defines, the program-cache
// key, the kernel specialization a result reports) and parse. Internal.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "snh/device.h"
#include "snh/material.h"
#include "snh/mesh.h"

namespace snh::device {

struct KernelConfig {
  std::optional<ElementType> element;         // SNH_HEX8 (hex8 1, tet4 0)
  bool general_material = false;              // SNH_GENERAL_KERNEL: the model read at run time
  std::optional<MaterialModel> model;         // SNH_MODEL
  std::optional<bool> barrier;                // SNH_BARRIER
  std::optional<bool> nonlinear;              // SNH_NONLINEAR: through the alpha/mixing parts
  std::optional<MaterialModel> lambda_model;  // SNH_LAMBDA_MODEL: the lambda part's model
  bool regions = false;                       // SNH_REGIONS: materials per element from a table
  std::optional<bool> uniform_rest;           // SNH_UNIFORM_REST: lattices' shared rest shape
  bool point_major = false;                   // SNH_POINT_MAJOR: hex8 per-point data point-major
  int cache_tile = 0;                         // SNH_CACHE_TILE (0: untiled)
  int stencil_tile = 0;                       // SNH_STENCIL_TILE (0: untiled)
  // The per-vertex terms (solver/model/vertex_terms.h, solver/contact/self_contact_terms.h).
  bool inertia = false;          // SNH_INERTIA
  int obstacles = 0;             // SNH_OBSTACLES
  bool self_contact = false;     // SNH_SELF_CONTACT
  bool self_barrier = false;     // SNH_SELF_BARRIER: barrier self-contact's blocks in block-Jacobi
  bool friction = false;         // SNH_FRICTION
  bool surface_contact = false;  // SNH_SURFACE_CONTACT: an embedded surface's points in obstacle contact
  // Switches of single programs.
  int lanes = 0;              // SNH_LANES: fem_lanes.cl's width (8 or 16)
  bool mixed = false;         // SNH_MIXED: float data, double p and results
  bool matrix_float = false;  // SNH_MATRIX_FLOAT: matrices or blocks stored in float
  bool float_cycle = false;   // SNH_FLOAT: a double build's float multigrid cycle
  int stencil_width = 0;      // SNH_STENCIL_WIDTH (0: an argument)
  int stencil_lower = 0;      // SNH_STENCIL_LOWER
  int fma_chains = 0;         // SNH_FMA_CHAINS (the benchmark's roofline)
  int cg_check = 0;           // SNH_CG_CHECK: cg.cl's iterations per convergence check (0: its default)
  int cg_span = 0;            // SNH_CG_SPAN: cg.cl's entries per reduction group (0: its default)
  bool gpu = false;           // SNH_GPU: the GPUs' build on any device (the context adds it on GPUs)
  // SNH_DOUBLE: set by the context that builds; not part of defines().
  std::optional<Precision> precision;

  // The switches, "-DSNH_HEX8=1 -DSNH_MODEL=0 ...", in the table's order
  // (precision left out): the program-cache key's part and an elastic
  // model's specialization (its ElementData's config).
  std::string defines() const;
  // defines() and -DSNH_DOUBLE: the kernel specialization a result reports
  // (SolveResult::kernel_specialization). Needs precision.
  std::string report() const;
  // The build options clBuildProgram gets: -cl-std=CL1.2, -DSNH_DOUBLE,
  // SNH_GPU on GPUs (`on_gpu`) or where set, and defines(). Needs precision.
  std::string build_options(bool on_gpu) const;
  // The program cache's key for kernels/<file>.
  std::string cache_key(const std::string& file) const { return file + '|' + defines(); }

  // Parses what defines() or report() writes (space-separated -DNAME=value);
  // snh::Error naming the switch for an unknown one or a bad value.
  static KernelConfig parse(const std::string& defines);

  // The same build with some switches changed.
  KernelConfig with_lanes(int n) const;
  KernelConfig with_mixed() const;
  KernelConfig with_matrix_float() const;
  KernelConfig with_float_cycle() const;
  KernelConfig with_stencil(int width, int lower) const;
  KernelConfig with_surface_contact() const;
  // Without the per-vertex terms (inertia, obstacles, self-contact (both
  // methods), friction, surface contact).
  KernelConfig elastic() const;

  bool operator==(const KernelConfig& o) const { return defines() == o.defines() && precision == o.precision; }
  bool operator!=(const KernelConfig& o) const { return !(*this == o); }
};

// The names of the switches the table knows, in its order (tests, docs).
std::vector<std::string> kernel_switch_names();

// A program an OpenClContext built: kernels/<file> with `config`.
struct BuiltProgram {
  std::string file;
  KernelConfig config;
};

// While one exists, every program any OpenClContext builds (not those it
// finds in its cache) is recorded here too, in build order: what a scene's
// setup or solve compiled (`snh programs`).
class ProgramRecorder {
 public:
  ProgramRecorder();
  ~ProgramRecorder();
  ProgramRecorder(const ProgramRecorder&) = delete;
  ProgramRecorder& operator=(const ProgramRecorder&) = delete;

  const std::vector<BuiltProgram>& programs() const { return programs_; }
  // Called by OpenClContext::program after a build.
  static void record(const std::string& file, const KernelConfig& config);

 private:
  std::vector<BuiltProgram> programs_;
};

}  // namespace snh::device
