#pragma once
// The traditional backend as the simulator sees it (core::Backend concept). For now it
// simulates particles; rigid bodies (issue #5) join here in this backend's algebra.
#include "traditional/particle.hpp"

#include <string_view>

namespace gacompare::traditional {

struct Backend : Particles {
  static constexpr std::string_view name = "traditional";
};

}  // namespace gacompare::traditional
