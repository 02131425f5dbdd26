// libFuzzer entry point for one surface reader, chosen at compile time with
// -DSNH_FUZZ_FORMAT=obj|ply|stl (see run.sh). The reader gets the input from
// memory; anything but snh::Error escaping it (a crash, a sanitizer report,
// another exception, a hang) is a bug. A surface that reads is also checked
// and voxelized coarsely (with -DSNH_FUZZ_SURFACE_REPORT), so welding, the
// defect counts and the winding numbers run on it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/surface_readers.h"
#include "snh/error.h"
#include "snh/surface.h"

#ifndef SNH_FUZZ_FORMAT
#error "define SNH_FUZZ_FORMAT as obj, ply or stl"
#endif
#define SNH_FUZZ_STR2(x) #x
#define SNH_FUZZ_STR(x) SNH_FUZZ_STR2(x)

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string format = SNH_FUZZ_STR(SNH_FUZZ_FORMAT);
  try {
    snh::TriangleSurface surface;
    if (format == "obj") {
      surface = snh::io::read_obj("fuzz.obj", input);
    } else if (format == "ply") {
      surface = snh::io::read_ply("fuzz.ply", input);
    } else if (format == "stl") {
      surface = snh::io::read_stl("fuzz.stl", input);
    }
#ifdef SNH_FUZZ_SURFACE_REPORT
    snh::surface_report(surface, "fuzz");
    // A coarse voxelization (about 8 cells across): welding, the fast
    // winding number and the gap rule on whatever the reader accepted.
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) lo[d] = hi[d] = surface.positions[d];
    for (size_t i = 0; i < surface.positions.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], surface.positions[i]);
      hi[i % 3] = std::max(hi[i % 3], surface.positions[i]);
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    snh::VoxelizeOptions options;
    options.max_grid_cells = 4096;
    snh::voxelize(surface, extent / 8, options);
#endif
  } catch (const snh::Error&) {
    // The documented outcome for bad input.
  }
  return 0;
}
