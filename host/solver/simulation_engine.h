// The device side of a Simulation in one precision: the elastic model on an
// OpenCL context, the Newton problem with its preconditioner, and the Newton
// driver over it. The main engine runs on the simulation's context; a float
// simulation's double fallback gets a context of its own.
#pragma once

#include <memory>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "snh/simulation.h"
#include "solver/device_problem.h"
#include "solver/elastic_model.h"
#include "solver/multigrid.h"
#include "solver/newton_driver.h"

namespace snh::solver {

template <typename Real>
struct SimulationEngine {
  std::unique_ptr<device::OpenClContext> own_context;  // the fallback's; null for the main engine
  long viennacl_context_id = 0;
  std::unique_ptr<ElasticModel<Real>> model;
  std::unique_ptr<DeviceProblem<Real>> problem;
  std::unique_ptr<NewtonDriver<DeviceProblem<Real>>> newton;
};

// What an engine is built from; the simulation owns all of it, and `options`
// must outlive the engine (its Newton driver reads them).
struct EngineSetup {
  const Mesh& mesh;
  const fem::RestState& rest;
  const MaterialMap& materials;
  const SolveOptions& options;
  const std::vector<char>& prescribed;  // per DOF
  Preconditioner preconditioner;        // resolved
  bool friction;
};

// The multigrid's options with the per-step rebuild resolved (off under
// dynamics unless asked for). The smoothing is resolved by the
// preconditioner itself, from the mesh and the model's materials
// (resolved_smoothing); the result reports what it used.
inline MultigridOptions resolved_multigrid_options(const SolveOptions& options) {
  MultigridOptions o = options.multigrid;
  if (!o.rebuild_each_load_step) o.rebuild_each_load_step = !options.dynamics.has_value();
  return o;
}

// An engine on `own` (bound to ViennaCL here), or on the main context
// `main` (ViennaCL context `main_viennacl_context`) when `own` is null.
// ViennaCL's current context is the main one again on return.
template <typename Real>
std::unique_ptr<SimulationEngine<Real>> make_engine(const EngineSetup& setup, device::OpenClContext& main,
                                                    long main_viennacl_context,
                                                    std::unique_ptr<device::OpenClContext> own,
                                                    ProductVariant variant) {
  auto engine = std::make_unique<SimulationEngine<Real>>();
  device::OpenClContext& ctx = own ? *own : main;
  engine->viennacl_context_id = own ? device::bind_viennacl(*own) : main_viennacl_context;
  engine->own_context = std::move(own);
  device::use_viennacl(engine->viennacl_context_id);
  const SolveOptions& options = setup.options;
  ModelTerms terms;
  terms.inertia = options.dynamics.has_value();
  terms.obstacles = static_cast<int>(options.obstacles.size());
  terms.self_contact = options.contact.self && options.contact.self_method == SelfContactMethod::penalty;
  terms.self_barrier = options.contact.self && options.contact.self_method == SelfContactMethod::barrier;
  terms.self_broad_phase = options.contact.self_broad_phase;
  terms.friction = setup.friction;
  engine->model = std::make_unique<ElasticModel<Real>>(ctx, setup.mesh, setup.rest, setup.materials, variant,
                                                       device::MaterialKernel::specialized, terms);
  std::vector<Real> mask(setup.prescribed.size());
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = setup.prescribed[i] ? Real(0) : Real(1);
  engine->model->set_mask(mask);
  if (terms.self_barrier && !options.contact.self_surface.triangles.empty())
    engine->model->set_self_barrier_surface(setup.mesh, options.contact.self_surface, options.contact.self_embedding);
  // Unset: float (the model keeps double for variants other than cached).
  engine->model->set_float_products(options.product_precision.value_or(Precision::single) == Precision::single);
  std::unique_ptr<MultigridPreconditioner<Real>> multigrid;
  if (setup.preconditioner == Preconditioner::multigrid) {
    std::vector<char> free(setup.prescribed.size());
    for (size_t i = 0; i < free.size(); ++i) free[i] = setup.prescribed[i] ? 0 : 1;
    multigrid = std::make_unique<MultigridPreconditioner<Real>>(*engine->model, setup.mesh, free,
                                                                resolved_multigrid_options(options));
  }
  engine->problem = std::make_unique<DeviceProblem<Real>>(*engine->model, setup.preconditioner, std::move(multigrid));
  // Tangled equilibria are perturbed by 1% of the vertex spacing
  // (solver/newton_driver.h).
  engine->problem->set_perturbation(mask, 1e-2 * vertex_spacing(setup.mesh));
  engine->problem->use_device_cg(options.cg_check_every);
  engine->newton = std::make_unique<NewtonDriver<DeviceProblem<Real>>>(*engine->problem, options);
  device::use_viennacl(main_viennacl_context);
  return engine;
}

}  // namespace snh::solver
