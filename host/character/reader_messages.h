// How the character readers word their errors: the file's path, then what
// is wrong, with numbers in the stream's shortest default form.
#pragma once

#include <sstream>
#include <string>

#include "snh/error.h"

namespace snh::detail {

[[noreturn]] inline void fail(const std::string& path, const std::string& what) { throw Error(path + ": " + what); }

inline std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace snh::detail
