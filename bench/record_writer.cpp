#include "record_writer.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "snh/error.h"

#ifndef SNH_BENCH_SCRIPT_DIR
#define SNH_BENCH_SCRIPT_DIR "bench"
#endif

namespace snh::bench {

namespace {

constexpr const char* kPython = "/usr/bin/python3";

}  // namespace

std::string csv_text(const Table& table) {
  std::string out;
  auto line = [&out](const std::vector<std::string>& cells) {
    for (size_t k = 0; k < cells.size(); ++k) out += (k == 0 ? "" : ",") + cells[k];
    out += '\n';
  };
  line(table.columns);
  for (const auto& row : table.rows) line(row);
  return out;
}

std::string markdown_text(const Table& table) {
  std::string out;
  auto line = [&out](const std::vector<std::string>& cells) {
    out += '|';
    for (const std::string& cell : cells) out += " " + cell + " |";
    out += '\n';
  };
  line(table.columns);
  for (size_t k = 0; k < table.columns.size(); ++k) out += "|---";
  out += "|\n";
  for (const auto& row : table.rows) line(row);
  return out;
}

std::string number(double value, int digits) {
  std::ostringstream s;
  s << std::setprecision(digits) << value;
  return s.str();
}

std::string significant(double value, int digits) { return std::isfinite(value) ? number(value, digits) : "-"; }

std::string fixed_digits(double value, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

std::string csv_number(double value) { return number(value, 9); }

std::string thousands(long long n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string mebibytes(size_t bytes) { return significant(static_cast<double>(bytes) / (1024.0 * 1024.0), 3); }

std::string csv_quoted(std::string text) {
  for (char& c : text)
    if (c == '"') c = '\'';
  return '"' + text + '"';
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw Error("cannot write " + path);
  file << text;
  file.close();
  if (file.fail()) throw Error("cannot write " + path);
}

void write_json(const std::string& path, const nlohmann::ordered_json& document) {
  write_text(path, document.dump(2) + '\n');
}

std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void draw_plots(const std::string& command, const std::string& script, const std::string& input,
                const std::string& out_dir) {
  const std::string path = std::string(SNH_BENCH_SCRIPT_DIR) + "/" + script;
  if (!std::filesystem::exists(kPython) || !std::filesystem::exists(path)) {
    std::cerr << command << ": warning: " << kPython << " or " << path << " not found; plots skipped\n";
    return;
  }
  const std::string line = std::string(kPython) + " " + shell_quoted(path) + " " + shell_quoted(input) + " " +
                           shell_quoted(out_dir) + " 1>&2";
  if (std::system(line.c_str()) != 0)
    std::cerr << command << ": warning: plotting failed or matplotlib is missing; plots skipped\n";
}

}  // namespace snh::bench
