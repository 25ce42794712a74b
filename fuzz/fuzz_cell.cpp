// libFuzzer target for the sweep's readers (compare/stored.hpp, what a resumed
// sweep and `gacompare merge` read): any bytes either read as a checked cell
// and as a checked manifest, or are refused with gacompare::Error; anything
// else is a bug.   scripts/fuzz.sh   (seeded with fuzz/seeds/cell)
#include "compare/stored.hpp"
#include "core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)gacompare::compare::parse_cell(text, "fuzz.json", "rk4-dt0.01");
  } catch (const gacompare::Error&) {
  }
  try {
    (void)gacompare::compare::parse_manifest(text, "sweep.json");
  } catch (const gacompare::Error&) {
  }
  return 0;
}
