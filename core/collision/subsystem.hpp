#pragma once
// A group of bodies integrated on its own: an island stepped alone, or the
// bodies of the pairs a time-of-impact search re-integrates.
#include "core/dynamics/ode.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <memory>
#include <optional>
#include <span>
#include <thread>
#include <vector>

namespace gacompare::core {

template <class Bodies>
class BodyBlocks;

// An island's bodies as a model of their own, their state copied out of the
// world's and back, and the scene's solver for them alone. A Lie-group method
// (rkmk4, rkmk45, crouch_grossman4) steps them through the backend's
// group_step of this model, wired as the world's solver is
// (set_group_step_of, core/dynamics/ode.hpp): every body's step reads only
// its own state and forces (core/dynamics/lie_bodies.hpp), so an island and
// a time-of-impact trial move on the group as they move in the world.
// The solver is built on the first integration, and its work vectors (ten
// of the island's state size, zeroed) on its first advance: a push-out only
// reads and moves the island's state, and an island integrated in blocks
// steps through the blocks' solvers, its own keeping the budget and the
// count; those vectors cost a pile of thousands of bodies megabytes.
template <class Bodies>
struct Subsystem {
  using Model = typename Bodies::Model;
  Model model;
  std::span<const int> group;
  std::size_t stride;
  Subsystem(const Model& m, std::span<const int> bodies, std::size_t stride_, const SolverSpec& spec)
      : model(Bodies::subset(m, bodies)), group(bodies), stride(stride_), spec_(spec) {}
  Subsystem(const Subsystem&) = delete;
  Subsystem& operator=(const Subsystem&) = delete;
  std::vector<double> gather(std::span<const double> y) const {
    std::vector<double> out(group.size() * stride);
    for_each_index(group.size(), [&](std::size_t k) {
      std::copy_n(y.begin() + static_cast<long>(group[k] * stride), stride, out.begin() + static_cast<long>(k * stride));
    }, kGrainBody);
    return out;
  }
  void scatter(const std::vector<double>& ys, std::span<double> y) const {
    for_each_index(group.size(), [&](std::size_t k) {
      std::copy_n(ys.begin() + static_cast<long>(k * stride), stride, y.begin() + static_cast<long>(group[k] * stride));
    }, kGrainBody);
  }
  // Integrates ys from t to t_end (the island's forces are timed as `forces`
  // in `profile`, like the world's; a Lie-group method evaluates them inside
  // its step and ignores f, timed as `integrate`, like the world's). A group
  // large enough is integrated in blocks on the run's threads, as the world
  // is (BodyBlocks): a pile's island stepped alone, its sub-steps and its
  // search's trials of the whole island.
  void integrate(double t, double t_end, std::vector<double>& ys, Profile& profile) {
    if (BodyBlocks<Bodies>::wanted(spec_.method, group.size())) {
      if (!blocks_) blocks_ = std::make_unique<BodyBlocks<Bodies>>();
      return blocks_->integrate(model, stride, solver(), t, t_end, ys, profile);
    }
    auto f = [&](double tt, std::span<const double> yy, std::span<double> dy) {
      ScopedStage timed(profile, Stage::forces);
      Bodies::derivative(model, tt, yy, dy);
    };
    auto after = [&](std::vector<double>& yy) { return Bodies::renormalise(model, yy); };
    solver().advance(f, t, t_end, ys, profile, after);
  }

  // The scene's solver for these bodies, built on first use.
  OdeSolver& solver() {
    if (solver_) return *solver_;
    OdeSolver& s = solver_.emplace(spec_, group.size() * stride);
    s.set_error_norm([this](std::span<const double> a, std::span<const double> b, std::span<const double> e) {
      return Bodies::error_ratio(model, a, b, e, spec_.abs_tol, spec_.rel_tol);
    });
    set_group_step_of<Bodies>(s, model);  // `model` is a member: it lives as long as the solver
    return s;
  }

 private:
  SolverSpec spec_;
  std::optional<OdeSolver> solver_;
  std::unique_ptr<BodyBlocks<Bodies>> blocks_;  // built on the first integration in blocks
};

// A model's bodies in one block per thread, each block integrated through a
// whole interval on its thread: the world's step (core/dynamics/simulation.hpp)
// and a large group's (Subsystem::integrate). The bodies move alone within
// the interval (forces act on each body alone; contacts come after it,
// core/collision/collision_step.hpp), and a fixed-step method's stages are
// sums taken number by number, so a block's numbers are the whole group's,
// bit for bit. Splitting each force evaluation across the threads instead
// (RigidBodies::derivative's loop) made two threads slower than one on the
// 10,000-body box: the stages' sums ran on one thread and read every other
// body's derivative from the other core's cache, four times a step. An
// adaptive method's step depends on every body's error, and a Lie-group
// method steps through the group's own step: those take the whole group's
// step. Below kBlockBodies bodies a block's work is about what waking a
// thread costs.
template <class Bodies>
class BodyBlocks {
 public:
  using Model = typename Bodies::Model;
  static constexpr std::size_t kBlockBodies = 64;

  // Whether `bodies` bodies stepped by `method` are integrated in blocks: on
  // several threads, not inside another loop's item (a block's own group).
  static bool wanted(SolverMethod method, std::size_t bodies) {
    return threads() > 1 && !detail::in_item() && (method == SolverMethod::rk4 || method == SolverMethod::euler) &&
           bodies >= grain_of(kBlockBodies) * static_cast<std::size_t>(threads());
  }

  // y, the state of m's bodies (`stride` doubles each), from t to t_end. The
  // steps count against `whole`, the solver of all of them: its budget is
  // checked before and its statistics take the blocks' steps after. The wall
  // time is the integrate stage's; the forces of the block that runs on the
  // run's own thread are timed as forces, as on one thread.
  void integrate(const Model& m, std::size_t stride, OdeSolver& whole, double t, double t_end, std::vector<double>& y,
                 Profile& profile) {
    ScopedStage timed(profile, Stage::integrate);
    const std::size_t n = y.size() / stride, count = static_cast<std::size_t>(threads());
    if (blocks_.size() != count) {
      blocks_.clear();
      bodies_.assign(count, {});
      states_.assign(count, {});
      for (std::size_t k = 0; k < count; ++k)
        for (std::size_t b = k * n / count; b < (k + 1) * n / count; ++b) bodies_[k].push_back(static_cast<int>(b));
      for (std::size_t k = 0; k < count; ++k) {
        blocks_.push_back(std::make_unique<Subsystem<Bodies>>(m, bodies_[k], stride, whole.spec()));
        blocks_.back()->solver().set_step_budget(0x1p53);  // the whole's solver keeps the budget
      }
    }
    whole.check_fixed_budget(t, t_end, y);
    const SolverStats before = blocks_[0]->solver().stats();
    const auto caller = std::this_thread::get_id();
    std::vector<Profile> elsewhere(count);  // a worker's stage times: its wall time is the caller's wait
    for_each_index(
        count,
        [&](std::size_t k) {
          Subsystem<Bodies>& block = *blocks_[k];
          std::vector<double>& ys = states_[k];  // the block's bodies are consecutive
          const auto first = y.begin() + static_cast<long>(block.group.front() * stride);
          ys.assign(first, first + static_cast<long>(block.group.size() * stride));
          block.integrate(t, t_end, ys, std::this_thread::get_id() == caller ? profile : elsewhere[k]);
          std::copy(ys.begin(), ys.end(), first);
        },
        1);
    whole.add_steps(before, blocks_[0]->solver().stats());
  }

 private:
  std::vector<std::vector<int>> bodies_;  // each block's bodies, consecutive
  std::vector<std::unique_ptr<Subsystem<Bodies>>> blocks_;
  std::vector<std::vector<double>> states_;  // kept: a fresh one each step cost page faults
};

}  // namespace gacompare::core
