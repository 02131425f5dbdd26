// libFuzzer entry point for the animation parsers (snh/animation.h), chosen
// at compile time with -DSNH_FUZZ_FORMAT=json|csv (see run.sh); fuzz_entry.h
// says what counts as a bug (also an exception such as one of
// nlohmann::json's).
#include "fuzz_entry.h"
#include "snh/animation.h"

#ifndef SNH_FUZZ_FORMAT
#error "define SNH_FUZZ_FORMAT as json or csv"
#endif
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return snh::fuzz::read_input(data, size, [](const std::string& input) {
    if (snh::fuzz::format == "json")
      snh::parse_animation_json(input, "fuzz.json");
    else
      snh::parse_animation_csv(input, "fuzz.csv");
  });
}
