// Saving and resuming a simulation: a Simulation's full state
// (Simulation::checkpoint, snh/simulation.h) written to and read from a
// versioned binary file. Doubles are stored as their bytes, so a state read
// back is bit for bit the one written, and a simulation restored from it
// continues exactly as the one that wrote it.
//
// File layout (version 1, the host's byte order, marked in the header): the
// 8 bytes "SNHSTATE", uint32 version, uint32 0x01020304; then the items of
// SimulationState in declaration order: integers as uint64, doubles as
// 8 bytes, bools as one byte, strings and arrays as a uint64 count followed
// by their elements. A RigidTransform's rotation is stored column-major
// (rotation[3 * row + col] at position 3 * col + row of its nine doubles),
// the order of the files written before the API went row-major.
#pragma once

#include <string>

#include "snh/simulation.h"

namespace snh {

// Throws snh::Error naming the path if the file cannot be written.
void write_checkpoint(const std::string& path, const SimulationState& state);

// Throws snh::Error naming the path and the item for a file that is not a
// checkpoint, of another version or byte order, truncated, with an item of
// the wrong size (e.g. positions not 3 values per vertex), or with bytes
// after the last item.
SimulationState read_checkpoint(const std::string& path);

}  // namespace snh
