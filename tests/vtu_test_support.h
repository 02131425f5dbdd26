// Reading back what write_vtu wrote, for the writer's and the fields' tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace snh::test {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The numbers of the DataArray named `name` in a .vtu written by write_vtu.
inline std::vector<double> read_array(const std::string& vtu, const std::string& name) {
  const size_t at = vtu.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const size_t begin = vtu.find('>', at) + 1, end = vtu.find("</DataArray>", at);
  std::istringstream in(vtu.substr(begin, end - begin));
  std::vector<double> values;
  double v;
  while (in >> v) values.push_back(v);
  return values;
}

}  // namespace snh::test
