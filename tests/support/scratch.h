// Fresh, emptied folders for the files a test writes, named with the
// process id so that parallel test processes do not share them.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace snh::test {

// <temp>/<name>_<pid>.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// <temp>/<prefix>_<pid>/<name>: one test file's folders side by side.
inline std::filesystem::path scratch_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace snh::test
