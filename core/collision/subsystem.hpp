#pragma once
// A group of bodies integrated on its own: an island stepped alone, or the
// bodies of the pairs a time-of-impact search re-integrates.
#include "core/dynamics/ode.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <optional>
#include <span>
#include <vector>

namespace gacompare::core {

// An island's bodies as a model of their own, their state copied out of the
// world's and back, and the scene's solver for them alone. A Lie-group method
// (rkmk4, rkmk45, crouch_grossman4) steps them through the backend's
// group_step of this model, wired as the world's solver is
// (set_group_step_of, core/dynamics/ode.hpp): every body's step reads only
// its own state and forces (core/dynamics/lie_bodies.hpp), so an island and
// a time-of-impact trial move on the group as they move in the world.
// The solver is built on the first integration: a push-out only reads and
// moves the island's state, and the solver's work vectors (ten of the
// island's state size, zeroed) cost a pile of thousands of bodies megabytes
// at every response.
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
  // its step and ignores f, timed as `integrate`, like the world's).
  void integrate(double t, double t_end, std::vector<double>& ys, Profile& profile) {
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
};

}  // namespace gacompare::core
