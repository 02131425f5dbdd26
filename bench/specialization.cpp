#include "specialization.h"

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

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "enum_names.h"
#include "fem/rest_state.h"
#include "material_options.h"
#include "record_writer.h"
#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/simulation.h"
#include "solver/model/elastic_model.h"
#include "timing.h"

namespace snh::bench {
namespace {

using json = nlohmann::ordered_json;

Material parse_material(const std::string& text) {
  snh::MaterialOptions o;
  const MaterialModel model = cli::parse_material_label(text, o);
  return Material::from_youngs_modulus(model, 1.0, 0.45, o);
}

// The same rest data stored per element (what a non-lattice mesh needs).
fem::RestState per_element(const fem::RestState& rest, size_t elements) {
  fem::RestState out = rest;
  if (!rest.uniform) return out;
  out.uniform = false;
  out.gradients.clear();
  out.weights.clear();
  for (size_t e = 0; e < elements; ++e) {
    out.gradients.insert(out.gradients.end(), rest.gradients.begin(), rest.gradients.end());
    out.weights.insert(out.weights.end(), rest.weights.begin(), rest.weights.end());
  }
  return out;
}

struct Timing {
  double energy = 0, residual = 0, linearize = 0, product = 0;  // seconds per call
};

// One element type, material and operation: seconds per call of each build.
struct SpecializationRecord {
  std::string element_type, material, operation;
  size_t elements = 0;
  double specialized = 0, general_material = 0, fully_general = 0, all_terms = 0;
  bool bitwise_equal = false;
  double all_terms_relative_difference = 0;
};

template <typename Real>
int run(const SpecializationOptions& o, json& report, std::ostringstream& md,
        std::vector<SpecializationRecord>& records) {
  const Precision precision = parse_precision(o.precision);
  device::OpenClContext cl(DeviceOptions{o.device}, precision);
  device::bind_viennacl(cl);
  report["device"] = cl.info().platform + " / " + cl.info().name;
  report["precision"] = o.precision;
  report["size"] = o.size;
  md << "# Kernel specialization\n\nDevice: " << cl.info().platform << " / " << cl.info().name << "; " << o.precision
     << "; box lattice " << o.size << "^3, deformed (x 0.9, 0.9, 1.3 plus noise); best of repeats over "
     << o.min_seconds << " s per operation. Builds: specialized (the engine's default: model, barrier, alpha/mixing "
     << "path and, on lattices, the shared rest shape fixed at build time), general material (model, barrier and "
     << "path read at run time), fully general (that and per-element rest data), all terms (specialized to the "
     << "model but always through the alpha/mixing parts, as a kernel carrying every term computes). Gains are "
     << "time(build) / time(specialized): above 1 the specialization wins.\n\n";
  int status = 0;
  for (const std::string& type : o.element_types) {
    const int n = o.size;
    const Mesh mesh = cli::element_type_named(type) == ElementType::hex8 ? make_box_lattice(n, n, n, 1.0 / n)
                                                                         : make_tet_box(n, n, n, 1.0 / n);
    const fem::RestState rest = fem::compute_rest_state(mesh);
    const fem::RestState rest_general = per_element(rest, mesh.element_count());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-0.1 / n, 0.1 / n), unit(-1.0, 1.0);
    const std::vector<double>& rest_xyz = mesh.positions.xyz();
    std::vector<Real> xh(rest_xyz.size()), ph(rest_xyz.size());
    for (size_t i = 0; i < xh.size(); ++i) {
      xh[i] = Real((i % 3 == 2 ? 1.3 : 0.9) * rest_xyz[i] + u(rng));
      ph[i] = Real(unit(rng));
    }
    viennacl::vector<Real> x(xh.size()), p(xh.size()), r(xh.size()), y(xh.size());
    viennacl::copy(xh.begin(), xh.end(), x.begin());
    viennacl::copy(ph.begin(), ph.end(), p.begin());
    for (const std::string& name : o.materials) {
      const Material material = parse_material(name);
      const struct {
        const fem::RestState* rest;
        device::MaterialKernel kernel;
      } builds[4] = {{&rest, device::MaterialKernel::specialized},
                     {&rest, device::MaterialKernel::runtime},
                     {&rest_general, device::MaterialKernel::runtime},
                     {&rest, device::MaterialKernel::all_terms}};
      Timing t[4];
      std::vector<Real> results[4];
      for (int b = 0; b < 4; ++b) {
        solver::ElasticModel<Real> model(cl, mesh, *builds[b].rest, uniform_material(mesh, material),
                                         ProductVariant::recompute, builds[b].kernel);
        t[b].energy = best_seconds([&] { model.energy(x); }, o.min_seconds);
        t[b].residual = best_seconds([&] { model.residual(x, r); }, o.min_seconds);
        t[b].linearize = best_seconds([&] { model.linearize(x); }, o.min_seconds);
        t[b].product = best_seconds([&] { model.product(p, y); }, o.min_seconds);
        results[b].resize(2 * xh.size());
        viennacl::copy(r.begin(), r.end(), results[b].begin());
        viennacl::copy(y.begin(), y.end(), results[b].begin() + static_cast<long>(xh.size()));
      }
      // The run-time builds evaluate the same expressions (no contraction):
      // bitwise equal on one device. The all-terms build sums the alpha/mixing
      // parts instead, equal up to rounding.
      const bool same = results[0] == results[1] && results[0] == results[2];
      double diff = 0.0, scale = 0.0;
      for (size_t i = 0; i < results[0].size(); ++i) {
        diff = std::max(diff, std::abs(double(results[3][i]) - double(results[0][i])));
        scale = std::max(scale, std::abs(double(results[0][i])));
      }
      const double parts_error = diff / scale;
      if (!same || !(parts_error < (sizeof(Real) == 8 ? 1e-9 : 1e-3))) status = 1;
      const std::pair<const char*, double Timing::*> ops[] = {{"energy", &Timing::energy},
                                                              {"residual", &Timing::residual},
                                                              {"linearize", &Timing::linearize},
                                                              {"product (recompute)", &Timing::product}};
      for (const auto& [op, field] : ops) {
        const double s = t[0].*field, g = t[1].*field, a = t[2].*field, all = t[3].*field;
        records.push_back({type, material.description(), op, mesh.element_count(), s, g, a, all, same, parts_error});
      }
      std::cerr << "  " << type << " " << material.description() << ": linearize gain " << std::fixed
                << std::setprecision(2) << t[1].linearize / t[0].linearize << " (material), "
                << t[2].linearize / t[0].linearize << " (all), " << t[3].linearize / t[0].linearize << " (terms)"
                << (same ? "" : "  RESULTS DIFFER") << '\n';
    }
  }
  return status;
}

}  // namespace

int run_specialization(const SpecializationOptions& o) {
  std::filesystem::create_directories(o.out);
  json report;
  std::ostringstream md;
  std::vector<SpecializationRecord> records;
  const int status = parse_precision(o.precision) == Precision::single ? run<float>(o, report, md, records)
                                                                       : run<double>(o, report, md, records);
  Table table;
  table.columns = {
      "element",      "material",        "op",         "specialized ms", "general material ms", "fully general ms",
      "all terms ms", "gain (material)", "gain (all)", "gain (terms)"};
  for (const SpecializationRecord& r : records) {
    const double s = r.specialized, g = r.general_material, a = r.fully_general, all = r.all_terms;
    table.add_row({r.element_type, r.material, r.operation, fixed_digits(1e3 * s, 3), fixed_digits(1e3 * g, 3),
                   fixed_digits(1e3 * a, 3), fixed_digits(1e3 * all, 3), fixed_digits(g / s, 2), fixed_digits(a / s, 2),
                   fixed_digits(all / s, 2)});
    report["rows"].push_back({{"element_type", r.element_type},
                              {"material", r.material},
                              {"operation", r.operation},
                              {"elements", r.elements},
                              {"specialized_ms", 1e3 * s},
                              {"general_material_ms", 1e3 * g},
                              {"fully_general_ms", 1e3 * a},
                              {"all_terms_ms", 1e3 * all},
                              {"gain_material", g / s},
                              {"gain_all", a / s},
                              {"gain_terms", all / s},
                              {"bitwise_equal", r.bitwise_equal},
                              {"all_terms_relative_difference", r.all_terms_relative_difference}});
  }
  md << markdown_text(table);
  // Geometric mean of the gains per operation, over materials and elements
  // (the all-terms gain over the materials as written only).
  struct Mean {
    double sum = 0.0;
    int count = 0;
    void add(double x) {
      sum += std::log(x);
      ++count;
    }
    double value() const { return count ? std::exp(sum / count) : 1.0; }
  };
  std::map<std::string, Mean> material_gain, all_gain, terms_gain;
  for (const json& row : report["rows"]) {
    const std::string op = row["operation"];
    material_gain[op].add(row["gain_material"].get<double>());
    all_gain[op].add(row["gain_all"].get<double>());
    if (row["material"].get<std::string>().find_first_of("+ ") == std::string::npos)
      terms_gain[op].add(row["gain_terms"].get<double>());
  }
  Table means;
  means.columns = {"op", "gain (material)", "gain (all)", "gain (terms, models as written)"};
  for (const auto& [op, g] : material_gain) {
    means.add_row({op, fixed_digits(g.value(), 2), fixed_digits(all_gain[op].value(), 2),
                   fixed_digits(terms_gain[op].value(), 2)});
    report["geometric_mean_gain"][op] = {
        {"material", g.value()}, {"all", all_gain[op].value()}, {"terms", terms_gain[op].value()}};
  }
  md << "\nGeometric mean of the gains per operation:\n\n" << markdown_text(means);
  if (status != 0)
    md << "\n**The builds' results differ** (see bitwise_equal and all_terms_relative_difference in "
          "specialization.json).\n";
  write_json(o.out + "/specialization.json", report);
  write_text(o.out + "/specialization.md", md.str());
  std::cout << md.str() << "wrote " << o.out << "/specialization.{md,json}\n";
  return status;
}

void add_specialization_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SpecializationOptions>();
  CLI::App* cmd = app.add_subcommand("specialization",
                                     "Gain of the per-scene specialized kernels over one general kernel, per material");
  cmd->add_option("--materials", o->materials, "MODEL, 'MODEL alpha=A' or MU_MODEL+lambda:LAMBDA_MODEL (comma list)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--element", o->element_types, "hex8, tet4 (comma list)")
      ->delimiter(',')
      ->check(CLI::IsMember(cli::element_type_names()))
      ->capture_default_str();
  cmd->add_option("--size", o->size, "cells per side of the box lattice")->capture_default_str();
  cmd->add_option("--precision", o->precision, "float or double")
      ->check(CLI::IsMember(cli::precision_names()))
      ->capture_default_str();
  cmd->add_option("--min-seconds", o->min_seconds, "time per measured operation")->capture_default_str();
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = run_specialization(*o); });
}

}  // namespace snh::bench
