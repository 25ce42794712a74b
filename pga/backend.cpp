// The simulator over the pga backend, instantiated once (backend.hpp
// declares it extern for every other translation unit).
#include "pga/backend.hpp"

namespace gacompare::core {
template Run simulate<pga::Backend>(const Scene&, std::shared_ptr<const Model>);
template Run simulate<pga::Backend>(const Scene&);
}  // namespace gacompare::core
