// The simulator over the traditional backend, instantiated once (backend.hpp
// declares it extern for every other translation unit).
#include "traditional/backend.hpp"

namespace gacompare::core {
template Run simulate<traditional::Backend>(const Scene&, std::shared_ptr<const Model>);
template Run simulate<traditional::Backend>(const Scene&);
}  // namespace gacompare::core
