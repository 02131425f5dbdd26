// The multigrid options that `scale` and `scene` share on the command line
// (MultigridOptions in snh/simulation.h): registered and applied once here.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "enum_names.h"
#include "snh/simulation.h"

namespace snh::cli {

struct MultigridFlags {
  int rebuild_every = 0;                // > 0: MultigridOptions::rebuild_every
  int smoother_degree = 0;              // > 0: MultigridOptions::smoother_degree
  int coarsest_dofs = 0;                // > 0: MultigridOptions::coarsest_dofs
  std::string chebyshev;                // non-empty: MultigridOptions::chebyshev_kind
  std::string fine_level = kAutomatic;  // MultigridOptions::fine_level (automatic: unset)
  std::string fine_float = "on";        // MultigridOptions::fine_level_float
  std::string float_cycle = "on";       // MultigridOptions::float_cycle
  std::string coarse_solve = "host";    // MultigridOptions::coarse_solve_on_device

  void add_to(CLI::App* cmd) {
    cmd->add_option("--multigrid-rebuild-every", rebuild_every,
                    "multigrid: rebuild the hierarchy at least every N Newton linearizations (1: every one; "
                    "default: MultigridOptions::rebuild_every)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--multigrid-smoother-degree", smoother_degree,
                    "multigrid: Chebyshev degree of each pre- and post-smoothing (default: automatic, "
                    "MultigridOptions::smoother_degree)")
        ->check(CLI::Range(1, 16));
    cmd->add_option("--multigrid-chebyshev", chebyshev,
                    "multigrid: the smoothing polynomial, first (first-kind Chebyshev on [0.1, 1.1] x the estimated "
                    "lambda_max), fourth or optimized-fourth (Lottes 2023, on [0, 1.1] x lambda_max; optimized: "
                    "degrees 1-4), or automatic (default: optimized-fourth of degree 1 under 600,000 DOFs and "
                    "nu < 0.495, else first of degree 2; MultigridOptions::chebyshev_kind)")
        ->check(CLI::IsMember(chebyshev_kind_names()));
    cmd->add_option("--multigrid-coarsest-dofs", coarsest_dofs,
                    "multigrid: coarsen until a level has at most this many DOFs, solved directly (default: "
                    "MultigridOptions::coarsest_dofs)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--multigrid-fine-level", fine_level,
                    "multigrid: the V-cycle's fine level, built (the build's element matrices, frozen with the "
                    "coarse levels), current (the product of each linearization) or automatic (built unless the "
                    "scene has inertia or obstacles)")
        ->check(CLI::IsMember(multigrid_fine_level_names()))
        ->capture_default_str();
    cmd->add_option("--multigrid-fine-float", fine_float,
                    "multigrid, double with a built fine level: its element matrices in float (on) or in double "
                    "(off)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cmd->add_option("--multigrid-float-cycle", float_cycle,
                    "multigrid, double with a built fine level: the V-cycle's vectors, stencils and smoother in "
                    "float (on; its builds and CG stay double) or in double (off)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cmd->add_option("--multigrid-coarse-solve", coarse_solve,
                    "multigrid: the coarsest level's solve by a Chebyshev polynomial on the device, no read "
                    "(device), or by its factor on the host, read back and written again in every V-cycle (host)")
        ->check(CLI::IsMember({"device", "host"}))
        ->capture_default_str();
  }

  void apply(MultigridOptions& options) const {
    if (rebuild_every > 0) options.rebuild_every = rebuild_every;
    if (smoother_degree > 0) options.smoother_degree = smoother_degree;
    if (!chebyshev.empty()) options.chebyshev_kind = parse_optional(chebyshev, parse_chebyshev_kind);
    if (coarsest_dofs > 0) options.coarsest_dofs = static_cast<size_t>(coarsest_dofs);
    options.fine_level = parse_optional(fine_level, parse_multigrid_fine_level);
    options.fine_level_float = fine_float == "on";
    options.float_cycle = float_cycle == "on";
    options.coarse_solve_on_device = coarse_solve == "device";
  }
};

}  // namespace snh::cli
