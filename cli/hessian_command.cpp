// `snh hessian SCENE --out PREFIX` (also `snh-gpu-bench hessian`): the engine's linear system at
// a Newton iterate of a built-in scene, written for study outside the engine
// (cli/hessian_export.h; bench/amg_study.py reads it).
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_commands.h"
#include "enum_names.h"
#include "hessian_export.h"
#include "snh/error.h"
#include "snh/scenes.h"

namespace snh::cli {
namespace {

struct HessianCommand {
  std::string name = "twist";
  int resolution = 0;
  std::string element = "tet4";
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.49;
  int newton_iterations = 2;
  std::string out;
  std::string device;
};

int run_hessian(const HessianCommand& o) {
  using Clock = std::chrono::steady_clock;
  SceneParameters p;
  if (o.resolution > 0) p.resolution = o.resolution;  // 0: unset
  p.youngs_modulus = o.youngs_modulus;
  p.poisson_ratio = o.poisson_ratio;
  p.element_type = parse_element_type(o.element);
  const Scene scene = make_scene(o.name, p);
  const MaterialMap materials = uniform_material(scene.mesh, scene.material);
  const auto t0 = Clock::now();
  const ExportedSystem s = export_scene_system(scene, materials, o.newton_iterations, o.device);
  const auto t1 = Clock::now();
  write_exported_system(o.out, scene.mesh, s);
  const auto t2 = Clock::now();

  double rhs_norm = 0.0;
  for (double v : s.rhs) rhs_norm += v * v;
  rhs_norm = std::sqrt(rhs_norm);
  nlohmann::ordered_json j;
  j["scene"] = scene.name;
  j["resolution"] = o.resolution;
  j["element_type"] = to_string(scene.mesh.type);
  j["elements"] = scene.mesh.element_count();
  j["vertices"] = scene.mesh.vertex_count();
  j["dofs"] = 3 * scene.mesh.vertex_count();
  j["free_dofs"] = s.free_dofs.size();
  j["nonzeros"] = s.matrix.nonZeros();
  j["youngs_modulus"] = scene.material.youngs_modulus();
  j["poisson_ratio"] = scene.material.poisson_ratio();
  j["newton_iterations"] = s.newton_iterations;
  j["rhs_norm"] = rhs_norm;
  j["seconds_solve_and_assemble"] = std::chrono::duration<double>(t1 - t0).count();
  j["seconds_write"] = std::chrono::duration<double>(t2 - t1).count();
  j["files"] = {o.out + ".mtx", o.out + "_rhs.mtx", o.out + "_dofs.csv"};
  std::ofstream(o.out + ".json") << j.dump(2) << '\n';
  std::cout << scene.name << " " << to_string(scene.mesh.type) << ": " << s.free_dofs.size() << " free of "
            << 3 * scene.mesh.vertex_count() << " DOFs, " << s.matrix.nonZeros() << " nonzeros, after "
            << s.newton_iterations << " Newton iterations of step 1, |r| = " << rhs_norm << "\nwrote: " << o.out
            << ".{mtx,_rhs.mtx,_dofs.csv,json}\n";
  return 0;
}

}  // namespace

void add_hessian_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<HessianCommand>();
  CLI::App* cmd = app.add_subcommand(
      "hessian",
      "Write a scene's linear system at a Newton iterate of its first load step: the projected stiffness on the free "
      "DOFs (Matrix Market), the residual and each free DOF's vertex and positions (for rigid-body modes)");
  cmd->add_option("scene", o->name, "built-in scene (twist, stretch, ...)")->capture_default_str();
  cmd->add_option("--res", o->resolution, "cells across the scene's thickness (0: scene default)");
  cmd->add_option("--element", o->element, "hex8 or tet4 (each lattice hex split in six)")
      ->check(CLI::IsMember(element_type_names()))
      ->capture_default_str();
  cmd->add_option("--E", o->youngs_modulus, "Young's modulus")->capture_default_str();
  cmd->add_option("--nu", o->poisson_ratio, "Poisson's ratio")->capture_default_str();
  cmd->add_option("--newton-iterations", o->newton_iterations,
                  "Newton updates of load step 1 before the system is taken (fewer if step 1 converges first)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--out", o->out, "path prefix of PREFIX.mtx, PREFIX_rhs.mtx, PREFIX_dofs.csv, PREFIX.json")
      ->required();
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->callback([o, &exit_code] { exit_code = run_hessian(*o); });
}

}  // namespace snh::cli
