// libFuzzer entry point for one mesh reader, chosen at compile time with
// -DSNH_FUZZ_FORMAT=msh|vtk|vtu|mesh|tetgen (see run.sh). The reader gets the
// input from memory; fuzz_entry.h says what counts as a bug. For TetGen
// the input is the .node file, a NUL byte, then the .ele file.
#include "fuzz_entry.h"
#include "io/readers.h"

#ifndef SNH_FUZZ_FORMAT
#error "define SNH_FUZZ_FORMAT as msh, vtk, vtu, mesh or tetgen"
#endif
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return snh::fuzz::read_input(data, size, [](const std::string& input) {
    const std::string& format = snh::fuzz::format;
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
  });
}
