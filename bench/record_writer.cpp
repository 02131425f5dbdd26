#include "record_writer.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "snh/error.h"

#ifndef SNH_BENCH_SCRIPT_DIR
#define SNH_BENCH_SCRIPT_DIR "bench"
#endif

namespace snh::bench {

namespace {

constexpr const char* kPython = "/usr/bin/python3";

}  // namespace

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
