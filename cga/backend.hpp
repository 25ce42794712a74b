#pragma once
// The cga backend as the simulator sees it (core::Backend concept). For now it
// simulates particles; rigid bodies (issue #5) join here in this backend's algebra.
#include "cga/particle.hpp"

#include <string_view>

namespace gacompare::cga {

struct Backend : Particles {
  static constexpr std::string_view name = "cga";
};

}  // namespace gacompare::cga
