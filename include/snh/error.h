// The one exception type the library throws: every message names the input,
// device or parameter at fault and what is wrong with it.
#pragma once

#include <stdexcept>
#include <string>

namespace snh {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace snh
