// traditional/particle.hpp through the simulator, against closed forms.
#include "traditional/backend.hpp"
#include "../particle_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, ParticleCases, traditional::Backend);
}
