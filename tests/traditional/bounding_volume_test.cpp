// traditional/bounding_volume.hpp (centre and radius, the distance test) through
// the shared bounding-volume cases.
#include "../collision_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, BoundingVolumeCases, traditional::SphereOps);
}  // namespace gacompare::testing
