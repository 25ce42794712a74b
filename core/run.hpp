#pragma once
// What a simulation run produces, backend-neutral: samples in world terms, the
// stage profile, solver statistics and counters. results.json is written from it.
#include "core/dynamics/ode.hpp"
#include "core/model/scene.hpp"
#include "core/stage.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gacompare::core {

struct ParticleSample {
  Vec3 position{0, 0, 0};
  Vec3 velocity{0, 0, 0};
};

struct BodySample {
  Vec3 position{0, 0, 0};
  Eigen::Vector4d orientation{1, 0, 0, 0};  // [w,x,y,z], body -> world
  Vec3 velocity{0, 0, 0};
  Vec3 angular_velocity{0, 0, 0};           // world frame
};

struct Sample {
  double t = 0;
  std::vector<ParticleSample> particles;  // in scene order
  std::vector<BodySample> bodies;         // in scene order
  double kinetic = 0, potential = 0;
  Vec3 linear_momentum{0, 0, 0};
  Vec3 angular_momentum{0, 0, 0};  // about the origin, world frame
  double constraint_violation = 0; // max over constraints of |C|/|∇C|, metres
  double rotation_drift = 0;       // max over bodies of ‖RᵀR − I‖, |q q* − 1| or |R R̃ − 1|
};

struct Run {
  std::string backend;
  std::vector<Sample> samples;
  Profile profile;
  SolverStats solver;
  std::map<std::string, std::uint64_t> counters;
  std::map<std::string, double> metrics;  // measured values that are not counts (largest CG residual)
  double wall_seconds = 0;          // whole run, start to last sample
  std::optional<std::string> error; // set when the run stopped early; samples so far are kept

  // A counter's value, 0 where the run has none (a stage it never entered).
  std::uint64_t count(const std::string& name) const {
    const auto it = counters.find(name);
    return it == counters.end() ? 0 : it->second;
  }
};

// The run's answer as one SHA-256 (64 hex digits): every sample's time and
// state (each double's bits, so that any change in the last place shows),
// the solver's steps and evaluations, every counter, and the error if the
// run stopped; not the timings, which differ from run to run. Equal hashes
// mean the same answer to the bit: the determinism check compares runs on 1
// and 2 threads and from gcc and clang.
std::string state_hash(const Run& run);

}  // namespace gacompare::core
