// The solver's configuration with every unset option chosen: what a
// Simulation runs with, and why. One function, resolve_configuration, turns
// the options, mesh, materials and device into it; the Simulation and
// everything it builds read only the result (Simulation::configuration).
// `snh run --explain SCENE` prints it and the scene's JSON summary carries
// it as its `resolved` object (docs/design.md, "The resolved configuration").
#pragma once

#include <string>
#include <vector>

#include "snh/device.h"
#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/regions.h"
#include "snh/simulation.h"

namespace snh {

// One resolved setting as printed: its option name (the scene file's and the
// command line's spelling), its value and why it has it ("given" when the
// options set it, else the rule that chose it).
struct ResolvedSetting {
  std::string name;
  std::string value;
  std::string reason;
};

struct ResolvedConfiguration {
  // The options with every unset (std::optional) value they use set to the
  // one chosen: preconditioner, product and product_precision always; with
  // multigrid its smoothing (smoother_degree, chebyshev_kind), fine level,
  // rebuilds and float V-cycle; with barrier self-contact its broad phase
  // and reach (contact.self_distance); with penalty self-contact its
  // stiffness; with friction the slip; and the stopping test
  // (absolute_tolerance carries the strain criterion's value,
  // strain_tolerance is cleared). Loads, targets and callbacks as given.
  SolveOptions options;
  // Barrier self-contact's stiffness kappa (0 without the barrier).
  double barrier_stiffness = 0.0;
  // Newton's stopping test (SolveOptions::strain_tolerance): the step ends
  // converged at |r| <= max(absolute_tolerance, relative_tolerance * |r_0|).
  double absolute_tolerance = 0.0;
  double relative_tolerance = 0.0;
  // Every choice above and the limits, in a fixed order, for printing.
  std::vector<ResolvedSetting> settings;

  // The setting named `name`; throws snh::Error when there is none.
  const ResolvedSetting& setting(const std::string& name) const;
};

// Resolves `options` for this mesh, these materials and this device.
// Throws snh::Error for combinations that cannot run (multigrid on a mesh
// that is not a hex8 lattice, multigrid with penalty self-contact, a built
// multigrid fine level with inertia, obstacles or the barrier).
ResolvedConfiguration resolve_configuration(const SolveOptions& options, const Mesh& mesh, const MaterialMap& materials,
                                            const DeviceInfo& device);

}  // namespace snh
