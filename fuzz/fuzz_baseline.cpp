// libFuzzer target for the baseline reader (compare/stored.hpp, what
// `gacompare check --baseline` reads): any bytes either read as a checked
// baseline or are refused with gacompare::Error; anything else is a bug.
//   scripts/fuzz.sh   (seeded with data/reference)
#include "compare/stored.hpp"
#include "core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto j = gacompare::compare::parse_stored(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    (void)gacompare::compare::parse_baseline(j, "fuzz.json");
  } catch (const gacompare::Error&) {
  }
  return 0;
}
