// libFuzzer target for the OBJ reader: any bytes either
// give a valid closed mesh or are refused with gacompare::Error; a mesh that
// loads also goes through what a body does with it (convexity, mass
// properties), which must not fail in any other way.
//   scripts/fuzz.sh --seconds 60   (seeded with tests/core/data/meshes)
#include "core/error.hpp"
#include "core/model/mass_properties.hpp"
#include "core/model/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const gacompare::core::Mesh mesh = gacompare::core::parse_obj(text, "fuzz.obj");
    (void)gacompare::core::convexity(mesh);
    (void)gacompare::core::mass_properties(mesh, 1.0);
  } catch (const gacompare::Error&) {
  }
  return 0;
}
