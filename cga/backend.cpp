// The simulator over the cga backend, instantiated once (backend.hpp
// declares it extern for every other translation unit).
#include "cga/backend.hpp"

namespace gacompare::core {
template Run simulate<cga::Backend>(const Scene&, std::shared_ptr<const Model>);
template Run simulate<cga::Backend>(const Scene&);
}  // namespace gacompare::core
