// Hard cases stay numerically stable: a fast off-axis spin (|ω| = 36
// rad/s, a 0.1 × 0.4 × 0.9 box) through every rotation representation × solver ×
// renormalisation policy, and what each keeps: the drift of the stored rotation
// from a rotation (‖RᵀR − I‖, |q q* − 1|, |R R̃ − 1|), the relative change of the
// kinetic energy and of |L| (both exact invariants: no torque), after the run.
//
//   rigid_stability [--steps N]     (default 100000 fixed steps of 1e-3 s; the
//                                    adaptive solvers run the same duration)
#include "cga/backend.hpp"
#include "pga/backend.hpp"
#include "core/dynamics/simulator.hpp"
#include "traditional/backend.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

namespace {
using namespace gacompare;

core::Scene scene(double duration, const char* method, const char* rotation, const char* renormalise) {
  char json[1024];
  std::snprintf(json, sizeof json,
                R"({"name": "spin", "duration": %.17g, "output": {"every": %.17g},
      "solver": {"method": "%s", "dt": 1e-3, "abs_tol": 1e-9, "rel_tol": 1e-9},
      "rigid_body": {"rotation": "%s", "renormalise": "%s"},
      "bodies": [{"name": "b", "shape": {"box": [0.1, 0.4, 0.9]}, "mass": 1.0, "position": [0, 0, 0],
                  "angular_velocity": [20.0, 5.0, 30.0]}]})",
                duration, duration / 100, method, rotation, renormalise);
  return core::parse_scene(json, "rigid_stability");
}

template <class B>
void row(const char* representation, const core::Scene& s) {
  const auto t0 = std::chrono::steady_clock::now();
  const core::Run run = core::simulate<B>(s);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& first = run.samples.front();
  const auto& last = run.samples.back();
  std::printf("| %s | %s | %s | %llu | ", representation, std::string(core::to_string(s.solver.method)).c_str(),
              s.rigid_body.renormalise == core::Renormalise::none ? "none" : "every step",
              static_cast<unsigned long long>(run.solver.steps_accepted));
  if (run.error) {  // a non-finite state: say when, from the run's own message
    const auto at = run.error->find("between");
    std::printf("diverged %s | | | %.3g s |\n", at == std::string::npos ? "" : run.error->substr(at).c_str(), secs);
    return;
  }
  std::printf("%.2e | %.2e | %.2e | %.3g s |\n", last.rotation_drift, std::abs(last.kinetic / first.kinetic - 1),
              std::abs(last.angular_momentum.norm() / first.angular_momentum.norm() - 1), secs);
}

}  // namespace

int main(int argc, char** argv) {
  long steps = 100000;
  if (argc == 3 && !std::strcmp(argv[1], "--steps")) {
    if (std::sscanf(argv[2], "%ld", &steps) != 1 || steps < 1) steps = 0;
  } else if (argc != 1) {
    steps = 0;
  }
  if (steps == 0) {
    std::fprintf(stderr, "usage: rigid_stability [--steps N]   (N a whole number >= 1)\n");
    return 2;
  }
  const double duration = static_cast<double>(steps) * 1e-3;
  std::printf("Fast off-axis spin, |ω| = 36 rad/s, %ld steps of 1e-3 s (adaptive: tolerance 1e-9, same %g s).\n\n",
              steps, duration);
  std::printf("| rotation | solver | renormalise | steps | drift from a rotation | ΔE / E | Δ‖L‖ / ‖L‖ | time |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|\n");
  for (const char* method : {"euler", "rk4", "cash_karp45"})
    for (const char* renorm : {"none", "every_step"}) {
      row<traditional::Backend>("matrix (traditional)", scene(duration, method, "matrix", renorm));
      row<traditional::Backend>("quaternion (traditional)", scene(duration, method, "quaternion", renorm));
      row<cga::Backend>("rotor (cga)", scene(duration, method, "matrix", renorm));
      row<pga::Backend>("motor (pga)", scene(duration, method, "matrix", renorm));
    }
  return 0;
}
