// The repository's data/ folder, which tests/CMakeLists.txt passes to the
// tests as SNH_DATA_DIR.
#pragma once

#include <filesystem>

#ifndef SNH_DATA_DIR
#error "SNH_DATA_DIR must name the data/ folder"
#endif

namespace snh::test {

inline std::filesystem::path data_dir() { return std::filesystem::path(SNH_DATA_DIR); }

}  // namespace snh::test
