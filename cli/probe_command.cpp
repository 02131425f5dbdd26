// `snh probe` (also `snh-gpu-bench probe`): the material on the OpenCL device, one JSON line in
// ({"F": [[row0], [row1], [row2]]}), one JSON line out per input line.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_commands.h"
#include "fem/matrix_order.h"
#include "fem/rest_state.h"
#include "material_options.h"
#include "snh/error.h"
#include "snh/probe.h"

namespace snh::cli {
namespace {

using json = nlohmann::ordered_json;

// Parses {"F": [[a,b,c],[d,e,f],[g,h,i]]} (rows) into row-major storage.
Matrix3 parse_deformation(const std::string& line) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(line);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(std::string("not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("F")) throw Error("expected an object with key \"F\"");
  for (const auto& item : doc.items())
    if (item.key() != "F") throw Error("unknown key \"" + item.key() + "\"");
  const nlohmann::json& f = doc["F"];
  if (!f.is_array() || f.size() != 3) throw Error("\"F\" must be an array of 3 rows");
  Matrix3 m{};
  for (int r = 0; r < 3; ++r) {
    if (!f[r].is_array() || f[r].size() != 3) throw Error("row " + std::to_string(r) + " of \"F\" must hold 3 numbers");
    for (int c = 0; c < 3; ++c) {
      if (!f[r][c].is_number()) throw Error("F[" + std::to_string(r) + "][" + std::to_string(c) + "] is not a number");
      m[3 * r + c] = f[r][c].get<double>();
    }
  }
  return m;
}

// The n x n matrix whose entry (r, c) is at(r, c), as n rows.
template <typename At>
json rows(int n, At at) {
  json out = json::array();
  for (int r = 0; r < n; ++r) {
    json row = json::array();
    for (int c = 0; c < n; ++c) row.push_back(at(r, c));
    out.push_back(row);
  }
  return out;
}

// `program`: the executable's name, for its messages.
int run_probe(const MaterialOptions& options, const std::string& program) {
  const Material material = options.material();
  MaterialProbe probe(material, parse_precision(options.precision), DeviceOptions{options.device});

  struct Line {
    long number;
    std::string error;
    size_t index = 0;
  };
  std::vector<Line> lines;
  std::vector<Matrix3> fs;
  std::string text;
  for (long number = 1; std::getline(std::cin, text); ++number) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      const Matrix3 f = parse_deformation(text);
      const double j = fem::determinant(fem::column_major_of(f).data());
      if (!material.defined_for_inversion() && !(j > 0.0))
        throw Error("the neohookean model without inversion handling (--j0 0) is undefined for J = det F = " +
                    std::to_string(j) + " <= 0");
      fs.push_back(f);
      lines.push_back({number, {}, fs.size() - 1});
    } catch (const Error& e) {
      lines.push_back({number, e.what()});
    }
  }
  const std::vector<ProbeResult> results = probe.evaluate(fs);
  int failures = 0;
  for (const Line& line : lines) {
    json out;
    if (!line.error.empty()) {
      ++failures;
      out["line"] = line.number;
      out["error"] = "line " + std::to_string(line.number) + ": " + line.error;
      std::cerr << program << " probe: line " << line.number << ": " << line.error << '\n';
    } else {
      const ProbeResult& r = results[line.index];
      out["line"] = line.number;
      out["psi"] = r.psi;
      out["P"] = rows(3, [&](int row, int col) { return r.P[3 * row + col]; });
      // H over the paper's vec(F) (index 3 * column + row), as printed
      // before; ProbeResult::H is over the row-major index.
      out["H"] = rows(9, [&](int i, int k) { return r.H[9 * fem::transposed_index(i) + fem::transposed_index(k)]; });
      out["eigenvalues"] = r.eigenvalues;
      out["sigma"] = r.sigma;
    }
    std::cout << out.dump() << '\n';
  }
  return failures == 0 ? 0 : 2;
}

}  // namespace

void add_probe_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<MaterialOptions>();
  CLI::App* cmd = app.add_subcommand(
      "probe",
      "Evaluate the material on the device. Reads JSON lines {\"F\": [[row0],[row1],[row2]]} from stdin and writes "
      "one JSON line each: psi, P (rows), H (projected 9x9 Hessian over vec(F), index 3*column+row), eigenvalues "
      "(nine, unprojected, ascending), sigma. A malformed line gets {\"line\": N, \"error\": ...}; exit status 2 "
      "then.");
  options->add_to(*cmd);
  cmd->callback([options, cmd, &exit_code] {
    exit_code = run_probe(*options, std::filesystem::path(cmd->get_parent()->get_name()).filename().string());
  });
}

}  // namespace snh::cli
