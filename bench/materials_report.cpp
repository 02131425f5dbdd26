#include "materials_report.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "enum_names.h"
#include "material/element_reference.h"
#include "material_options.h"
#include "record_writer.h"
#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"

namespace snh::bench {
namespace {

using json = nlohmann::ordered_json;

struct MaterialsOptions {
  std::vector<std::string> models{"snh",          "fung",      "arruda-boyce", "corotational", "fixed-corotational",
                                  "stvk-kikuuwe", "neohookean"};
  std::vector<double> poisson{0.2, 0.3, 0.4, 0.49};
  // Alpha and mixing rows of the stretch table: Stable Neo-Hookean at these alphas,
  // and these mixtures (MU_MODEL+lambda:LAMBDA_MODEL, Eq. 19).
  std::vector<double> alphas{0.5, 2.0};
  std::vector<std::string> mixes{"corotational+lambda:neohookean", "stvk-kikuuwe+lambda:snh"};
  // Alphas of the per-model uniaxial curves (Chen and Barbic 2024, Fig. 3).
  std::vector<double> curve_alphas{0.5, 0.75, 1.0, 1.5, 2.0};
  int resolution = 4;
  std::string precision = "double";
  std::string device;
  std::string out = "bench-results";
  bool plots = true;
};

// Homogeneous uniaxial stretch s along x, lateral stretch t free: t minimizes
// psi(diag(s, t, t)) (golden section on [0.05, 2]); returns P_xx, the
// nominal stress, and t.
std::pair<double, double> uniaxial(const Material& m, double s) {
  const auto spec = reference::spec_of(m);
  auto psi = [&](double t) { return reference::material_energy<double>({s, 0, 0, 0, t, 0, 0, 0, t}, spec); };
  double a = 0.05, b = 2.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  for (int i = 0; i < 200; ++i) {
    if (psi(c) < psi(d))
      b = d;
    else
      a = c;
    c = b - g * (b - a);
    d = a + g * (b - a);
  }
  const double t = 0.5 * (a + b);
  return {reference::material_pk1<double>({s, 0, 0, 0, t, 0, 0, 0, t}, spec)[0], t};
}

int run_materials(const MaterialsOptions& o) {
  std::filesystem::create_directories(o.out);
  json report;
  std::ostringstream md;
  md << "# Materials\n\nStretch scene (3.4x, resolution " << o.resolution << ", E = 1), volume change and CG "
     << "iterations per model and Poisson's ratio. Paper (nu = 0.49, 306,406 hexes): Stable Neo-Hookean +4.3%, "
        "filtered Neo-Hookean +4.9%, fixed co-rotational +4.5%, co-rotational -83%.\n\n";
  Table stretch;
  stretch.columns = {"model"};
  for (double nu : o.poisson) stretch.columns.push_back("nu " + number(nu, 6));
  Table csv;
  csv.columns = {
      "model",  "nu", "converged", "volume_change", "cg_iterations", "newton_iterations", "min_j", "inverted_elements",
      "seconds"};
  struct Row {
    std::string label;
    MaterialModel model;
    snh::MaterialOptions options;
  };
  std::vector<Row> rows;
  for (const std::string& name : o.models) rows.push_back({name, parse_material_model(name), {}});
  for (double alpha : o.alphas) {
    snh::MaterialOptions mo;
    mo.alpha = alpha;
    std::ostringstream label;
    label << "snh alpha=" << alpha;
    rows.push_back({label.str(), MaterialModel::stable_neo_hookean, mo});
  }
  for (const std::string& mix : o.mixes) {
    if (mix.find("+lambda:") == std::string::npos)
      throw Error("materials: a mix reads MU_MODEL+lambda:LAMBDA_MODEL, got '" + mix + "'");
    snh::MaterialOptions mo;
    const MaterialModel model = cli::parse_material_label(mix, mo);
    rows.push_back({mix, model, mo});
  }
  for (const Row& row : rows) {
    const std::string& name = row.label;
    std::vector<std::string> cells{name};
    for (double nu : o.poisson) {
      SceneParameters p;
      p.resolution = o.resolution;
      p.poisson_ratio = nu;
      const Scene scene = make_scene("stretch", p);
      SolveOptions options = scene.options;
      options.precision = parse_precision(o.precision);
      options.device.match = o.device;
      std::string cell;
      try {
        const Material material = Material::from_youngs_modulus(row.model, 1.0, nu, row.options);
        QuasistaticSolver solver(scene.mesh, material, scene.constraints, options);
        const SolveResult r = solver.solve();
        int cg = 0, newton = 0;
        for (const StepResult& s : r.steps) {
          cg += s.cg_iterations;
          newton += s.newton_iterations;
        }
        const double change = 100.0 * (r.volume_ratio - 1.0);
        std::ostringstream c;
        c << std::showpos << std::fixed << std::setprecision(1) << change << "%" << std::noshowpos << ", " << cg
          << " CG" << (r.converged ? "" : " (not converged)");
        cell = c.str();
        csv.add_row({'"' + name + '"', number(nu, 6), r.converged ? "1" : "0", number(change, 6), std::to_string(cg),
                     std::to_string(newton), number(r.min_j, 6), std::to_string(r.inverted_elements),
                     number(r.seconds, 6)});
        report["stretch"].push_back({{"model", name},
                                     {"nu", nu},
                                     {"converged", r.converged},
                                     {"volume_change_percent", change},
                                     {"cg_iterations", cg},
                                     {"newton_iterations", newton},
                                     {"min_j", r.min_j},
                                     {"inverted_elements", r.inverted_elements}});
      } catch (const Error& e) {
        cell = std::string("error: ") + e.what();
      }
      cells.push_back(cell);
      std::cerr << "  stretch " << name << " nu " << nu << ": " << cell << '\n';
    }
    stretch.add_row(std::move(cells));
  }
  md << markdown_text(stretch);
  write_text(o.out + "/materials_stretch.csv", csv_text(csv));
  // Uniaxial curves (host reference, double): per model, and per
  // nonlinearity setting for the hardening models.
  Table curves;
  curves.columns = {"curve", "stretch", "nominal_stress", "lateral_stretch"};
  struct Curve {
    std::string label;
    Material material;
  };
  std::vector<Curve> list;
  for (const std::string& name : o.models)
    list.push_back({name, Material::from_youngs_modulus(parse_material_model(name), 1.0, 0.45)});
  for (double g : {0.1, 0.3}) {
    snh::MaterialOptions mo;
    mo.fung_gamma = g;
    list.push_back({"fung gamma=" + std::to_string(g).substr(0, 3),
                    Material::from_youngs_modulus(MaterialModel::fung, 1.0, 0.45, mo)});
  }
  for (double b : {0.05, 0.3}) {
    snh::MaterialOptions mo;
    mo.arruda_boyce_beta1 = b;
    list.push_back({"arruda-boyce beta1=" + std::to_string(b).substr(0, 4),
                    Material::from_youngs_modulus(MaterialModel::arruda_boyce, 1.0, 0.45, mo)});
  }
  for (const Curve& c : list)
    for (int i = 0; i <= 60; ++i) {
      const double s = 0.5 + 2.5 * i / 60.0;
      const auto [stress, t] = uniaxial(c.material, s);
      curves.add_row({'"' + c.label + '"', number(s, 6), number(stress, 6), number(t, 6)});
    }
  write_text(o.out + "/materials_uniaxial.csv", csv_text(curves));
  // Chen and Barbic 2024, Fig. 3: each model's curve per alpha (same slope at stretch 1).
  Table alpha_curves;
  alpha_curves.columns = {"model", "alpha", "stretch", "nominal_stress", "lateral_stretch"};
  for (const std::string& name : o.models)
    for (double alpha : o.curve_alphas) {
      snh::MaterialOptions mo;
      mo.alpha = alpha;
      const Material m = Material::from_youngs_modulus(parse_material_model(name), 1.0, 0.45, mo);
      for (int i = 0; i <= 60; ++i) {
        const double s = 0.5 + 2.5 * i / 60.0;
        const auto [stress, t] = uniaxial(m, s);
        alpha_curves.add_row({name, number(alpha, 6), number(s, 6), number(stress, 6), number(t, 6)});
      }
    }
  write_text(o.out + "/materials_alpha.csv", csv_text(alpha_curves));
  write_json(o.out + "/materials.json", report);
  write_text(o.out + "/materials.md", md.str() +
                                          "\nUniaxial force-stretch curves (E = 1, nu = 0.45): "
                                          "materials_uniaxial.csv, materials_uniaxial.png; per model and "
                                          "nonlinearity alpha (Chen and Barbic 2024, Fig. 3): materials_alpha.csv, "
                                          "materials_alpha.png.\n");
  std::cout << md.str();
  if (o.plots) {
    const std::string cmd = "/usr/bin/python3 " + std::string(SNH_BENCH_SCRIPT_DIR) + "/plot_materials.py " + o.out +
                            "/materials_uniaxial.csv " + o.out + "/materials_uniaxial.png";
    const std::string alpha_cmd = "/usr/bin/python3 " + std::string(SNH_BENCH_SCRIPT_DIR) + "/plot_materials.py " +
                                  o.out + "/materials_alpha.csv " + o.out + "/materials_alpha.png";
    if (std::system(cmd.c_str()) != 0 || std::system(alpha_cmd.c_str()) != 0)
      std::cerr << "snh-gpu-bench materials: warning: no plot (matplotlib?)\n";
  }
  std::cout << "wrote " << o.out
            << "/materials.{md,json}, materials_stretch.csv, materials_uniaxial.{csv,png}, materials_alpha.{csv,png}\n";
  return 0;
}

}  // namespace

void add_materials_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MaterialsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "materials", "Stretch comparison of every material model over Poisson's ratios, and uniaxial curves");
  cmd->add_option("--models", o->models, "models (comma list)")->delimiter(',')->capture_default_str();
  cmd->add_option("--nu", o->poisson, "Poisson's ratios (comma list)")->delimiter(',')->capture_default_str();
  cmd->add_option("--alphas", o->alphas,
                  "alphas of the Stable Neo-Hookean rows (Chen and Barbic 2024, Eq. 16; comma list)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--mixes", o->mixes,
                  "mixture rows MU_MODEL+lambda:LAMBDA_MODEL (Chen and Barbic 2024, Eq. 19; comma list)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--curve-alphas", o->curve_alphas, "alphas of the per-model uniaxial curves (comma list)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--res", o->resolution, "stretch scene resolution")->capture_default_str();
  cmd->add_option("--precision", o->precision, "float or double")
      ->check(CLI::IsMember(cli::precision_names()))
      ->capture_default_str();
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_flag("!--no-plots", o->plots, "skip the PNG");
  cmd->callback([o, &exit_code] { exit_code = run_materials(*o); });
}

}  // namespace snh::bench
