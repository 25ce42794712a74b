#pragma once
// Stage timing (docs/architecture.md "Stage names"): one Stage enum, one Profile per run,
// filled by a scoped timer so timing never clutters the mathematics. Times are
// exclusive: entering a nested stage pauses the enclosing one, so the stage
// times of a run add up to the time spent inside stages.
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gacompare::core {

enum class Stage : int {
  forces, constraints, integrate, broadphase, narrowphase, time_of_impact, response,
  mass_properties, bounding_volumes,
  count
};
inline constexpr int kStageCount = static_cast<int>(Stage::count);

std::string_view stage_name(Stage s);
std::optional<Stage> stage_from_name(std::string_view name);

struct StageTime {
  double seconds = 0;
  std::uint64_t calls = 0;
};

class Profile {
 public:
  using Clock = std::chrono::steady_clock;

  const StageTime& operator[](Stage s) const { return stages_[static_cast<int>(s)]; }
  // A stage that never ran is absent from results and reports.
  bool ran(Stage s) const { return (*this)[s].calls > 0; }
  double total_seconds() const {
    double t = 0;
    for (const auto& s : stages_) t += s.seconds;
    return t;
  }

 private:
  friend class ScopedStage;
  std::array<StageTime, kStageCount> stages_{};
  int current_ = -1;  // the stage being timed, -1 outside all stages
  Clock::time_point since_{};
};

// Times one stage for its scope. Two clock reads per scope.
class ScopedStage {
 public:
  ScopedStage(Profile& p, Stage s) : p_(p), outer_(p.current_) {
    const auto now = Profile::Clock::now();
    if (outer_ >= 0) p_.stages_[outer_].seconds += std::chrono::duration<double>(now - p_.since_).count();
    p_.current_ = static_cast<int>(s);
    p_.since_ = now;
  }
  ~ScopedStage() {
    const auto now = Profile::Clock::now();
    auto& st = p_.stages_[p_.current_];
    st.seconds += std::chrono::duration<double>(now - p_.since_).count();
    ++st.calls;
    p_.current_ = outer_;
    p_.since_ = now;
  }
  ScopedStage(const ScopedStage&) = delete;
  ScopedStage& operator=(const ScopedStage&) = delete;

 private:
  Profile& p_;
  int outer_;
};

}  // namespace gacompare::core
