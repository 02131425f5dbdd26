// QuasistaticSolver: one solve over a Simulation from its start.
#include "snh/simulation.h"

namespace snh {

QuasistaticSolver::QuasistaticSolver(Mesh mesh, const Material& material, std::vector<ConstraintSet> constraints,
                                     SolveOptions options)
    : simulation_(std::move(mesh), material, std::move(constraints), std::move(options)) {}
QuasistaticSolver::QuasistaticSolver(Mesh mesh, const MaterialMap& materials, std::vector<ConstraintSet> constraints,
                                     SolveOptions options)
    : simulation_(std::move(mesh), materials, std::move(constraints), std::move(options)) {}
QuasistaticSolver::~QuasistaticSolver() = default;
QuasistaticSolver::QuasistaticSolver(QuasistaticSolver&&) noexcept = default;
QuasistaticSolver& QuasistaticSolver::operator=(QuasistaticSolver&&) noexcept = default;

const Mesh& QuasistaticSolver::mesh() const { return simulation_.mesh(); }
const DeviceInfo& QuasistaticSolver::device() const { return simulation_.device(); }
Simulation& QuasistaticSolver::simulation() { return simulation_; }

SolveResult QuasistaticSolver::solve(const ProgressCallback& progress, const StepCallback& on_step) {
  simulation_.restart();
  return simulation_.solve(0, progress, on_step);
}

}  // namespace snh
