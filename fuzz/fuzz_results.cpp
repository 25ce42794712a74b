// libFuzzer target for the results.json reader (compare/stored.hpp, what
// `gacompare diff` reads): any bytes either read as a checked results.json or
// are refused with gacompare::Error. Anything else (a crash, a sanitizer
// report, another exception such as nlohmann's, a hang, a memory blow-up) is a
// bug.   scripts/fuzz.sh   (seeded with fuzz/seeds/results)
#include "compare/stored.hpp"
#include "core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)gacompare::compare::parse_results(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const gacompare::Error&) {
  }
  return 0;
}
