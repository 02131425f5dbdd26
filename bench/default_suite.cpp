// The default suite: what the engine can measure today. For each precision and
// barrier setting, the element kernel (SVD, energy, PK1, closed-form
// eigensystem, projected Hessian) over random and extreme deformation
// gradients on the device: throughput, and error against the host reference
// in double precision.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <vector>

#include "commands.h"
#include "errtime.h"
#include "fem/matrix_order.h"
#include "material/element_reference.h"
#include "record_writer.h"
#include "scale.h"
#include "snh/device.h"
#include "snh/error.h"
#include "snh/probe.h"
#include "specialization.h"
#include "throughput.h"

namespace snh::bench {
namespace {

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// Random F with singular values spanning compression to 10x stretch,
// reflections and near-degeneracies, under random rotations, each as the
// host reference's column-major vec(F).
std::vector<reference::Mat3<double>> sample_deformations(int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<reference::Mat3<double>> out;
  out.reserve(count);
  for (int n = 0; n < count; ++n) {
    reference::Mat3<double> f;
    const double scale = std::pow(10.0, unit(rng));  // 0.1 .. 10
    for (double& x : f) x = scale * unit(rng);
    if (n % 7 == 0) f = reference::Mat3<double>{1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (n % 11 == 0)
      for (int c = 0; c < 3; ++c) f[3 * c + 2] = 1e-6 * f[3 * c + 2];  // crushed towards a plane
    out.push_back(f);
  }
  return out;
}

double relative_error(const double* device, const double* reference, int n, double scale) {
  double diff = 0.0, norm = 0.0;
  for (int i = 0; i < n; ++i) {
    diff += (device[i] - reference[i]) * (device[i] - reference[i]);
    norm += reference[i] * reference[i];
  }
  return std::sqrt(diff) / std::max(std::sqrt(norm), scale);
}

struct CaseResult {
  std::string device;
  std::string precision;
  bool barrier;
  int samples;
  double seconds;
  double max_error_pk1;
  double max_error_hessian;
  bool all_finite;
};

CaseResult run_case(Precision precision, bool barrier, const std::vector<reference::Mat3<double>>& fs) {
  const StableNeoHookean material =
      StableNeoHookean::from_youngs_modulus(1.0, barrier ? 0.3 : 0.45, barrier ? Barrier::on : Barrier::off);
  std::vector<Matrix3> rows;  // the probe's row-major order
  rows.reserve(fs.size());
  for (const auto& f : fs) rows.push_back(fem::row_major_of(f));
  MaterialProbe probe(material, precision);
  probe.evaluate({rows.front()});  // build the program outside the timing
  const auto start = Clock::now();
  const std::vector<ProbeResult> results = probe.evaluate(rows);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();

  const reference::SnhParameters params{material.mu, material.lambda, material.barrier};
  CaseResult r{
      probe.device().name, to_string(precision), barrier, static_cast<int>(fs.size()), seconds, 0.0, 0.0, true};
  for (size_t n = 0; n < fs.size(); ++n) {
    const auto pk1 = reference::snh_pk1<double>(fs[n], params);
    std::array<double, 81> h{};
    for (int c = 0; c < 9; ++c) {
      reference::Mat3<double> unit{};
      unit[c] = 1.0;
      const auto column = reference::snh_projected_action<double>(fs[n], unit, params);
      std::copy(column.begin(), column.end(), h.begin() + 9 * c);
    }
    const ProbeResult& d = results[n];
    for (double x : d.H) r.all_finite = r.all_finite && std::isfinite(x);
    for (double x : d.P) r.all_finite = r.all_finite && std::isfinite(x);
    // The device's P and H in the reference's vec order, h[9 c + r] = d vec(P)_r / d vec(F)_c.
    const auto p = fem::column_major_of(d.P);
    std::array<double, 81> dh;
    for (int c = 0; c < 9; ++c)
      for (int k = 0; k < 9; ++k) dh[9 * c + k] = d.H[9 * fem::transposed_index(k) + fem::transposed_index(c)];
    r.max_error_pk1 = std::max(r.max_error_pk1, relative_error(p.data(), pk1.data(), 9, material.mu));
    r.max_error_hessian = std::max(r.max_error_hessian, relative_error(dh.data(), h.data(), 81, material.mu));
  }
  return r;
}

// The element check: device kernels over random and extreme F against the
// host reference, with element-kernel throughput. Writes element.{json,md}.
int run_element_check(const std::string& out_dir, int samples, json& summary_out, std::string& md_out) {
  const std::vector<DeviceInfo> devices = list_devices();
  if (devices.empty()) throw Error("OpenCL: no OpenCL platform or device found");
  const std::vector<reference::Mat3<double>> fs = sample_deformations(samples, 2018);

  std::vector<CaseResult> cases;
  std::string device_name;
  for (Precision precision : {Precision::single, Precision::double_}) {
    for (bool barrier : {true, false}) {
      try {
        cases.push_back(run_case(precision, barrier, fs));
        device_name = cases.back().device;
      } catch (const Error& e) {
        std::cerr << "snh-gpu-bench: skipped " << to_string(precision) << " case: " << e.what() << '\n';
      }
    }
  }
  std::cerr << "  element check done\n";

  json summary;
  summary["device"] = device_name;
  summary["samples"] = samples;
  summary["error_metric"] =
      "max over F of ||X_device - X_reference||_F / max(||X_reference||_F, mu); reference: host, double";
  Table table;
  table.columns = {"precision", "barrier", "F per second", "max rel. error P", "max rel. error H", "all finite"};
  std::cout << "element kernel on " << device_name << " (" << samples << " deformation gradients per case)\n";
  std::cout << std::left << std::setw(10) << "precision" << std::setw(9) << "barrier" << std::setw(14) << "F/s"
            << std::setw(14) << "err P" << std::setw(14) << "err H"
            << "finite\n";
  for (const CaseResult& c : cases) {
    const double rate = c.samples / c.seconds;
    summary["cases"].push_back({{"precision", c.precision},
                                {"barrier", c.barrier},
                                {"samples", c.samples},
                                {"seconds", c.seconds},
                                {"evaluations_per_second", rate},
                                {"max_relative_error_pk1", c.max_error_pk1},
                                {"max_relative_error_hessian", c.max_error_hessian},
                                {"all_finite", c.all_finite}});
    std::cout << std::left << std::setw(10) << c.precision << std::setw(9) << (c.barrier ? "on" : "off")
              << std::setw(14) << std::setprecision(4) << rate << std::setw(14) << std::setprecision(3)
              << c.max_error_pk1 << std::setw(14) << c.max_error_hessian << (c.all_finite ? "yes" : "NO") << '\n';
    table.add_row({c.precision, c.barrier ? "on" : "off", number(rate, 4), number(c.max_error_pk1, 3),
                   number(c.max_error_hessian, 3), c.all_finite ? "yes" : "NO"});
  }
  write_json(out_dir + "/element.json", summary);
  write_text(out_dir + "/element.md", "# Element kernel\n\nDevice: " + device_name + "\n\n" + markdown_text(table));
  summary_out = summary;
  md_out = markdown_text(table);
  bool ok = !cases.empty();
  for (const CaseResult& c : cases) ok = ok && c.all_finite;
  return ok ? 0 : 1;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

int run_default_suite(const std::string& out_dir, int samples, bool quick) {
  const auto start = Clock::now();
  std::filesystem::create_directories(out_dir);
  std::cerr << "snh-gpu-bench default suite -> " << out_dir
            << "/ (element check, throughput, specialization, errtime, scale)\n";
  json summary;
  std::string element_md;
  int status = run_element_check(out_dir, samples, summary["element"], element_md);

  ThroughputOptions throughput;
  throughput.out = out_dir;
  throughput.sizes = quick ? std::vector<int>{2} : std::vector<int>{8, 12};
  throughput.min_seconds = quick ? 0.01 : 0.1;
  std::cerr << "throughput\n";
  status = std::max(status, run_throughput(throughput));

  // The gain of per-scene kernels over general ones, on three materials (the
  // full table: `snh-gpu-bench specialization`).
  SpecializationOptions specialization;
  specialization.out = out_dir;
  specialization.materials = {"snh", "corotational", "snh alpha=2"};
  specialization.element_types = {"hex8"};
  specialization.size = quick ? 2 : 12;
  specialization.min_seconds = quick ? 0.01 : 0.05;
  std::cerr << "specialization\n";
  status = std::max(status, run_specialization(specialization));

  ErrtimeOptions errtime;
  errtime.out_dir = out_dir;
  if (quick) {
    errtime.scenes = {"twist"};
    errtime.resolution = 2;
    errtime.plots = false;
  }
  std::cerr << "errtime\n";
  status = std::max(status, run_errtime(errtime));

  // A small scale run (the paper's sizes: `snh-gpu-bench scale --max-dofs`).
  ScaleOptions scale;
  scale.out_dir = out_dir;
  scale.resolutions = quick ? std::vector<int>{2, 3} : std::vector<int>{4, 6, 8};
  if (quick) scale.plots = false;
  std::cerr << "scale\n";
  write_scale(scale, run_scale(scale));

  for (const char* part : {"throughput", "specialization", "errtime", "scale"}) {
    std::ifstream in(out_dir + "/" + part + ".json");
    if (in) summary[part] = json::parse(in);
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  summary["suite_seconds"] = seconds;
  write_json(out_dir + "/summary.json", summary);
  write_text(out_dir + "/summary.md",
             "# snh-gpu-bench default suite\n\nDevice: " + summary["element"].value("device", std::string("?")) + "; " +
                 number(seconds, 3) + " s in all.\n\n## Element kernel\n\n" + element_md + "\n" +
                 read_file(out_dir + "/throughput.md") + "\n" + read_file(out_dir + "/specialization.md") + "\n" +
                 read_file(out_dir + "/errtime.md") + "\n" + read_file(out_dir + "/scale.md"));
  std::cout << "wrote " << out_dir
            << "/summary.{json,md} (and element, throughput, specialization, errtime, scale files) in "
            << std::setprecision(3) << seconds << " s\n";
  return status;
}

}  // namespace snh::bench
