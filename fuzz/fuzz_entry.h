// What every libFuzzer entry point here shares: the input as text, the
// format chosen at compile time with -DSNH_FUZZ_FORMAT=... (run.sh), and the
// rule that snh::Error is the one documented outcome for bad input, so that
// anything else escaping the reader (a crash, a sanitizer report, another
// exception, a hang) reaches libFuzzer as a bug.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "snh/error.h"

#define SNH_FUZZ_STR2(x) #x
#define SNH_FUZZ_STR(x) SNH_FUZZ_STR2(x)

namespace snh::fuzz {

#ifdef SNH_FUZZ_FORMAT
// The -DSNH_FUZZ_FORMAT this harness was built for, e.g. "msh".
inline const std::string format = SNH_FUZZ_STR(SNH_FUZZ_FORMAT);
#endif

// `read(input)` on the fuzzer's bytes; snh::Error is caught, anything else
// escapes. libFuzzer's return value (always 0).
template <typename Read>
int read_input(const uint8_t* data, size_t size, Read read) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  try {
    read(input);
  } catch (const snh::Error&) {
    // The documented outcome for bad input.
  }
  return 0;
}

}  // namespace snh::fuzz
