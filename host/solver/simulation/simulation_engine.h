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
#include "snh/configuration.h"
#include "snh/simulation.h"
#include "solver/model/elastic_model.h"
#include "solver/multigrid/multigrid.h"
#include "solver/newton/device_problem.h"
#include "solver/newton/newton_driver.h"

namespace snh::solver {

template <typename Real>
struct SimulationEngine {
  std::unique_ptr<device::OpenClContext> own_context;  // the fallback's; null for the main engine
  long viennacl_context_id = 0;
  std::unique_ptr<ElasticModel<Real>> model;
  std::unique_ptr<DeviceProblem<Real>> problem;
  std::unique_ptr<NewtonDriver<DeviceProblem<Real>>> newton;
};

// What an engine is built from; the simulation owns all of it, and `config`
// must outlive the engine (its Newton driver reads its options).
struct EngineSetup {
  const Mesh& mesh;
  const fem::RestState& rest;
  const MaterialMap& materials;
  const ResolvedConfiguration& config;
  const std::vector<char>& prescribed;  // per DOF
};

// An engine on `own` (bound to ViennaCL here), or on the main context
// `main` (ViennaCL context `main_viennacl_context`) when `own` is null.
// ViennaCL's current context is the main one again on return.
template <typename Real>
std::unique_ptr<SimulationEngine<Real>> make_engine(const EngineSetup& setup, device::OpenClContext& main,
                                                    long main_viennacl_context,
                                                    std::unique_ptr<device::OpenClContext> own) {
  auto engine = std::make_unique<SimulationEngine<Real>>();
  device::OpenClContext& ctx = own ? *own : main;
  engine->viennacl_context_id = own ? device::bind_viennacl(*own) : main_viennacl_context;
  engine->own_context = std::move(own);
  device::use_viennacl(engine->viennacl_context_id);
  const SolveOptions& options = setup.config.options;
  const ModelTerms terms = model_terms(options);
  engine->model = std::make_unique<ElasticModel<Real>>(ctx, setup.mesh, setup.rest, setup.materials, *options.product,
                                                       device::MaterialKernel::specialized, terms);
  std::vector<Real> mask(setup.prescribed.size());
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = setup.prescribed[i] ? Real(0) : Real(1);
  engine->model->set_mask(mask);
  if (terms.self_barrier && !options.contact.self_surface.triangles.empty())
    engine->model->contact().set_self_barrier_surface(setup.mesh, options.contact.self_surface,
                                                      options.contact.self_embedding);
  // Contact's constants, set once: the barrier's reach and stiffness, the
  // penalty's stiffness.
  if (terms.self_barrier)
    engine->model->contact().set_self_barrier(*options.contact.self_distance, setup.config.barrier_stiffness);
  if (terms.self_contact) engine->model->contact().set_self_contact_stiffness(*options.contact.self_stiffness);
  engine->model->products().set_float_products(options.product_precision == Precision::single);
  std::unique_ptr<MultigridPreconditioner<Real>> multigrid;
  if (options.preconditioner == Preconditioner::multigrid) {
    std::vector<char> free(setup.prescribed.size());
    for (size_t i = 0; i < free.size(); ++i) free[i] = setup.prescribed[i] ? 0 : 1;
    multigrid = std::make_unique<MultigridPreconditioner<Real>>(*engine->model, setup.mesh, free, options.multigrid);
  }
  engine->problem =
      std::make_unique<DeviceProblem<Real>>(*engine->model, *options.preconditioner, std::move(multigrid));
  // Tangled equilibria are perturbed by 1% of the vertex spacing
  // (solver/newton/newton_driver.h).
  engine->problem->set_perturbation(mask, 1e-2 * vertex_spacing(setup.mesh));
  engine->problem->use_device_cg(options.cg_check_every);
  engine->newton = std::make_unique<NewtonDriver<DeviceProblem<Real>>>(*engine->problem, options);
  device::use_viennacl(main_viennacl_context);
  return engine;
}

}  // namespace snh::solver
