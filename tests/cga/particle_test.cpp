// cga/particle.hpp through the simulator, against closed forms.
#include "cga/backend.hpp"
#include "../particle_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, ParticleCases, cga::Backend);
}
