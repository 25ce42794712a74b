#include "core/stage.hpp"

namespace gacompare::core {

namespace {
constexpr std::array<std::string_view, kStageCount> kNames = {
    "forces", "constraints", "integrate", "broadphase", "narrowphase", "time_of_impact",
    "response", "referee", "mass_properties", "bounding_volumes"};
}

std::string_view stage_name(Stage s) { return kNames[static_cast<int>(s)]; }

std::optional<Stage> stage_from_name(std::string_view name) {
  for (int i = 0; i < kStageCount; ++i)
    if (kNames[i] == name) return static_cast<Stage>(i);
  return std::nullopt;
}

}  // namespace gacompare::core
