// libFuzzer entry point for one mesh reader, chosen at compile time with
// -DSNH_FUZZ_FORMAT=msh|vtk|vtu|mesh|tetgen (see run.sh). The reader gets the
// input from memory; anything but snh::Error escaping it (a crash, a
// sanitizer report, another exception, a hang) is a bug. For TetGen the
// input is the .node file, a NUL byte, then the .ele file.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "io/readers.h"
#include "snh/error.h"

#ifndef SNH_FUZZ_FORMAT
#error "define SNH_FUZZ_FORMAT as msh, vtk, vtu, mesh or tetgen"
#endif
#define SNH_FUZZ_STR2(x) #x
#define SNH_FUZZ_STR(x) SNH_FUZZ_STR2(x)

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string format = SNH_FUZZ_STR(SNH_FUZZ_FORMAT);
  try {
    if (format == "msh") {
      snh::io::read_gmsh("fuzz.msh", input);
    } else if (format == "vtk") {
      snh::io::read_vtk_legacy("fuzz.vtk", input);
    } else if (format == "vtu") {
      snh::io::read_vtu("fuzz.vtu", input);
    } else if (format == "mesh") {
      snh::io::read_medit("fuzz.mesh", input);
    } else if (format == "tetgen") {
      const size_t nul = input.find('\0');
      const std::string node = input.substr(0, nul);
      const std::string ele = nul == std::string::npos ? std::string() : input.substr(nul + 1);
      snh::io::read_tetgen("fuzz.node", node, "fuzz.ele", ele);
    }
  } catch (const snh::Error&) {
    // The documented outcome for bad input.
  }
  return 0;
}
