// libFuzzer entry point for one surface reader, chosen at compile time with
// -DSNH_FUZZ_FORMAT=obj|ply|stl (see run.sh). The reader gets the input from
// memory; fuzz_entry.h says what counts as a bug. A surface that reads is
// also checked and voxelized coarsely (with -DSNH_FUZZ_SURFACE_REPORT), so
// welding, the defect counts and the winding numbers run on it.
#include <algorithm>

#include "fuzz_entry.h"
#include "io/surface_readers.h"
#include "snh/surface.h"

#ifndef SNH_FUZZ_FORMAT
#error "define SNH_FUZZ_FORMAT as obj, ply or stl"
#endif
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return snh::fuzz::read_input(data, size, [](const std::string& input) {
    snh::TriangleSurface surface;
    if (snh::fuzz::format == "obj") {
      surface = snh::io::read_obj("fuzz.obj", input);
    } else if (snh::fuzz::format == "ply") {
      surface = snh::io::read_ply("fuzz.ply", input);
    } else if (snh::fuzz::format == "stl") {
      surface = snh::io::read_stl("fuzz.stl", input);
    }
#ifdef SNH_FUZZ_SURFACE_REPORT
    snh::surface_report(surface, "fuzz");
    // A coarse voxelization (about 8 cells across): welding, the fast
    // winding number and the gap rule on whatever the reader accepted.
    const std::vector<double>& xyz = surface.positions.xyz();
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) lo[d] = hi[d] = xyz[d];
    for (size_t i = 0; i < xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], xyz[i]);
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    snh::VoxelizeOptions options;
    options.max_grid_cells = 4096;
    snh::voxelize(surface, extent / 8, options);
#endif
  });
}
