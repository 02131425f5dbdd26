// libFuzzer entry point for the animation parsers (snh/animation.h), chosen
// at compile time with -DSNH_FUZZ_FORMAT=json|csv (see run.sh). Anything but
// snh::Error escaping the parser (a crash, a sanitizer report, another
// exception such as one of nlohmann::json's, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "snh/animation.h"
#include "snh/error.h"

#ifndef SNH_FUZZ_FORMAT
#error "define SNH_FUZZ_FORMAT as json or csv"
#endif
#define SNH_FUZZ_STR2(x) #x
#define SNH_FUZZ_STR(x) SNH_FUZZ_STR2(x)

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string format = SNH_FUZZ_STR(SNH_FUZZ_FORMAT);
  try {
    if (format == "json")
      snh::parse_animation_json(input, "fuzz.json");
    else
      snh::parse_animation_csv(input, "fuzz.csv");
  } catch (const snh::Error&) {
    // The documented outcome for bad input.
  }
  return 0;
}
