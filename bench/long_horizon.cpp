// The long-horizon table: the free rigid body over many periods at a fixed
// step, every Lie-group method (core/dynamics/lie_group.hpp) through every
// rotation representation, and what each keeps: the energy's relative error at
// the end and its drift rate (the least-squares slope of ΔE/E over the run),
// |L|'s relative error (the world L = R Π), the stored rotation's distance from
// a rotation (‖RᵀR − I‖, |q q* − 1|, |R R̃ − 1|), and the median time of the
// repeats with their spread.
//
//   long_horizon [--periods N] [--repeat R] [--markdown]
//     (default 1,000 periods, 3 repeats; --periods 10000 for the full table;
//      --markdown prints the page's tables, docs/results/long-horizon.md)
#include "cga/rotation_group.hpp"
#include "core/dynamics/lie_group.hpp"
#include "pga/rotation_group.hpp"
#include "traditional/rotation_group.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

namespace {
using namespace gacompare;
using core::lie::GroupMethod;

struct Scene {
  const char* name;
  core::lie::FreeBody body;
  Eigen::Vector3d omega;  // body frame, at t = 0 (R = identity)
  double period;          // s
  long steps_per_period;
  const char* period_is;
};

// (a) A symmetric top (the rigid tests' 0.2 × 0.2 × 0.8 box, 3 kg) spun at 20
// rad/s about its axis, tilted by 1.5 rad/s: its axis precesses about L once
// per 2π I₁/|L|. (b) The Dzhanibekov body (0.1 × 0.4 × 0.9 box, 1 kg) spun at
// 10 rad/s about its intermediate axis with 0.1 rad/s nudges about the
// others: it flips once per the elliptic period of Euler's equations.
std::vector<Scene> scenes() {
  const core::lie::FreeBody top{{3.0 / 12 * 0.68, 3.0 / 12 * 0.68, 3.0 / 12 * 0.08}, {}};
  const Eigen::Vector3d top_w(1.5, 0, 20);
  const double top_period = 2 * std::numbers::pi * top.inertia.x() / top.inertia.cwiseProduct(top_w).norm();
  const core::lie::FreeBody flip{{(0.16 + 0.81) / 12, (0.01 + 0.81) / 12, (0.01 + 0.16) / 12}, {}};
  const Eigen::Vector3d flip_w(0.1, 10, 0.1);
  return {{"symmetric top", top, top_w, top_period, 500, "precession"},
          {"Dzhanibekov (intermediate axis)", flip, flip_w,
           core::lie::free_period(flip.inertia, flip.inertia.cwiseProduct(flip_w)), 400, "flip"}};
}

struct Row {
  std::string method, representation;
  double energy = 0, momentum = 0, drift = 0, rate = 0;  // rate: ΔE/E per 1,000 periods
  std::vector<double> seconds;
};

template <core::lie::RotationGroup G>
Row measure(GroupMethod m, const Scene& s, long periods, int repeat) {
  Row row{std::string(core::lie::to_string(m)), std::string(G::name), 0, 0, 0, 0, {}};
  const core::lie::State<G> y0{G::identity(), s.body.inertia.cwiseProduct(s.omega)};
  const double e0 = core::lie::energy(s.body, y0.momentum), l0 = core::lie::world_momentum(y0).norm();
  const long n = periods * s.steps_per_period;
  const double T = static_cast<double>(periods) * s.period;
  const long stride = std::max(1L, n / 10000);  // ≤ 10⁴ samples for the slope
  for (int r = 0; r < repeat; ++r) {
    double st = 0, se = 0, stt = 0, ste = 0, count = 0;
    long k = 0;
    const auto t0 = std::chrono::steady_clock::now();
    const auto y = core::lie::integrate(m, s.body, 0.0, T, n, y0, [&](double t, const core::lie::State<G>& state) {
      if (++k % stride) return;
      const double e = core::lie::energy(s.body, state.momentum) / e0 - 1, p = t / s.period;
      st += p, se += e, stt += p * p, ste += p * e, count += 1;
    });
    row.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    row.energy = core::lie::energy(s.body, y.momentum) / e0 - 1;
    row.momentum = core::lie::world_momentum(y).norm() / l0 - 1;
    row.drift = G::drift(y.rotation);
    row.rate = 1000 * (count * ste - st * se) / (count * stt - st * st);
  }
  return row;
}

template <core::lie::RotationGroup... Gs>
std::vector<Row> rows(const Scene& s, long periods, int repeat) {
  std::vector<Row> out;
  for (const auto m : core::lie::kGroupMethods) (out.push_back(measure<Gs>(m, s, periods, repeat)), ...);
  return out;
}

std::string time_cell(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g s (%.3g–%.3g)", t[t.size() / 2], t.front(), t.back());
  return buf;
}

void print(const Scene& s, const std::vector<Row>& table, long periods, bool markdown) {
  const long n = periods * s.steps_per_period;
  if (markdown)
    std::printf("\n### %s\n\n%ld periods (%s period %.4g s), %ld steps of %.4g s.\n\n"
                "| method | representation | ΔE / E | Δ‖L‖ / ‖L‖ | drift from a rotation | ΔE / E per 10³ periods | time (median, min–max) |\n"
                "|---|---|---:|---:|---:|---:|---:|\n",
                s.name, periods, s.period_is, s.period, n, s.period / static_cast<double>(s.steps_per_period));
  else
    std::printf("\n%s: %ld periods (%s period %.4g s), %ld steps of %.4g s\n%-24s %-26s %10s %10s %10s %12s  %s\n",
                s.name, periods, s.period_is, s.period, n, s.period / static_cast<double>(s.steps_per_period),
                "method", "representation", "dE/E", "d|L|/|L|", "drift", "dE/E/1e3per", "time");
  for (const Row& r : table) {
    if (markdown)
      std::printf("| %s | %s | %.2e | %.2e | %.2e | %.2e | %s |\n", r.method.c_str(), r.representation.c_str(), r.energy,
                  r.momentum, r.drift, r.rate, time_cell(r.seconds).c_str());
    else
      std::printf("%-24s %-26s %10.2e %10.2e %10.2e %12.2e  %s\n", r.method.c_str(), r.representation.c_str(), r.energy,
                  r.momentum, r.drift, r.rate, time_cell(r.seconds).c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  long periods = 1000;
  int repeat = 3;
  bool markdown = false, ok = true;
  for (int i = 1; i < argc && ok; ++i) {
    if (!std::strcmp(argv[i], "--markdown")) markdown = true;
    else if (!std::strcmp(argv[i], "--periods") && i + 1 < argc) ok = std::sscanf(argv[++i], "%ld", &periods) == 1 && periods >= 10;
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) ok = std::sscanf(argv[++i], "%d", &repeat) == 1 && repeat >= 1;
    else ok = false;
  }
  if (!ok) {
    std::fprintf(stderr, "usage: long_horizon [--periods N] [--repeat R] [--markdown]   (N >= 10, R >= 1)\n");
    return 2;
  }
  for (const Scene& s : scenes())
    print(s, rows<traditional::MatrixGroup, traditional::QuaternionGroup, cga::RotorGroup, pga::MotorGroup>(s, periods, repeat),
          periods, markdown);
  return 0;
}
