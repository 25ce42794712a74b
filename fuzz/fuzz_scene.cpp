// libFuzzer target for the scene loader: any bytes either
// load as a scene or are refused with gacompare::Error. Anything else (a crash,
// a sanitizer report, another exception, a hang past -timeout, memory past
// -rss_limit_mb) is a bug. Meshes resolve against tests/core/data, so a mutated
// seed that names meshes/cube.obj reaches the OBJ reader and the hull.
//   scripts/fuzz.sh --seconds 60   (seeded with data/scenes)
#include "core/error.hpp"
#include "core/model/model.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const gacompare::core::Compiled compiled =
        gacompare::core::parse_compiled(text, std::string(GACOMPARE_TEST_DATA_DIR) + "/fuzz.json");
    (void)compiled;
  } catch (const gacompare::Error&) {
  }
  return 0;
}
