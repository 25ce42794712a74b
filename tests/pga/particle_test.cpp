// pga/particle.hpp through the simulator, against closed forms.
#include "pga/backend.hpp"

#include "../particle_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, ParticleCases, pga::Backend);
}
