// What an snh::Error says, for the tests of messages.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "snh/error.h"

namespace snh::test {

// The message of the snh::Error that f throws; a failure of the test when it
// throws none.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no snh::Error was thrown";
  return "";
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace snh::test
