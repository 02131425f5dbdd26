// The OpenCL sources under kernels/, embedded into the binary at build time
// (cmake/embed_kernels.cmake), with their local #include lines resolved.
#pragma once

#include <string>

namespace snh::device {

// The full text of kernels/<name> with every `#include "..."` of another
// embedded file inlined once, ready for clCreateProgramWithSource.
std::string kernel_program_source(const std::string& name);

}  // namespace snh::device
