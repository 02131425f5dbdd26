// The engine's linear systems written out for study outside it (e.g.
// algebraic multigrid in PyAMG, bench/amg_study.py): a scene is run for a
// chosen number of Newton iterations of its first load step, and the
// PSD-projected stiffness at that state (the host reference assembly,
// reference/fem_reference.h, the same matrix the device's products apply),
// restricted to the free DOFs, is written as Matrix Market with the residual
// and, per free DOF, its vertex, component and rest and current positions
// (from which the six rigid-body modes are built).
#pragma once

#include <Eigen/Sparse>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/regions.h"
#include "snh/scenes.h"

namespace snh::cli {

struct ExportedSystem {
  // Full DOF index (3 vertex + component) of each free DOF, ascending.
  std::vector<int64_t> free_dofs;
  // The projected stiffness on the free DOFs (free x free).
  Eigen::SparseMatrix<double> matrix;
  // The residual -dE/dx (elastic forces plus external force) on the free DOFs.
  std::vector<double> rhs;
  // The state linearized at, xyz per vertex.
  std::vector<double> positions;
  int newton_iterations = 0;  // Newton updates of load step 1 behind `positions`
};

// The DOFs no constraint set prescribes and that belong to an element
// (DOF 3 v + i), ascending.
std::vector<int64_t> free_dofs(const Mesh& mesh, const std::vector<ConstraintSet>& constraints);

// The system at `positions`: the projected stiffness and residual on the
// free DOFs of `constraints` (`external_force`: lumped, xyz per vertex, or empty).
ExportedSystem linear_system_at(const Mesh& mesh, const MaterialMap& materials,
                                const std::vector<ConstraintSet>& constraints, const std::vector<double>& positions,
                                const std::vector<double>& external_force = {});

// Runs `scene` (its own options, with the device match given) through
// `newton_iterations` Newton updates of load step 1 (fewer if it converges)
// and returns the system at the state reached.
ExportedSystem export_scene_system(const Scene& scene, const MaterialMap& materials, int newton_iterations,
                                   const std::string& device_match = "");

// Writes prefix.mtx (the matrix, "coordinate real symmetric", lower
// triangle, 17 significant digits), prefix_rhs.mtx ("array real general",
// one column) and prefix_dofs.csv (free index, vertex, component, rest
// x y z, current x y z). Throws snh::Error naming the file it cannot write.
void write_exported_system(const std::string& prefix, const Mesh& mesh, const ExportedSystem& system);

// Reads a "coordinate real symmetric" or "coordinate real general" Matrix
// Market file (the tests read back what write_exported_system wrote).
Eigen::SparseMatrix<double> read_matrix_market(const std::string& path);

}  // namespace snh::cli
