#include "compare/collide.hpp"

#include "cga/narrowphase.hpp"
#include "pga/narrowphase.hpp"
#include "compare/machine.hpp"
#include "compare/referee.hpp"
#include "compare/stats.hpp"
#include "core/error.hpp"
#include "core/collision/separating_axis.hpp"
#include "traditional/narrowphase.hpp"

#include <Eigen/Geometry>

#include <cctype>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <map>
#include <numbers>
#include <sstream>

namespace gacompare::compare {

namespace {

using collision::PairContact;
using Clock = std::chrono::steady_clock;
const std::size_t kReference = 6;  // "sat" in collide_methods()

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json answer(const PairContact& r, double seconds) {
  return {{"intersect", r.intersect}, {"depth", r.depth},       {"normal", vec(r.normal)},
          {"contact", vec(r.contact)}, {"feature", collision::feature_name(r.feature)}, {"time_s", seconds}};
}

std::string slug(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out.substr(0, 60);
}

// What the simulation runs at a pair's first detection: both shapes placed
// afresh (reset: the same pose again would be kept as it is), no axis
// remembered.
template <class Body>
PairContact first_meeting(typename Body::Shape& a, typename Body::Shape& b, const collision::CollisionCase& c,
                          std::vector<collision::FeatureContact>& found) {
  found.clear();
  a.reset(), b.reset();
  a.place(c.a()), b.place(c.b());
  return collision::narrowphase<Body>(a, b, collision::Method::sat_then_manifold, &found);
}

}  // namespace

nlohmann::json case_json(const collision::CollisionCase& c) {
  const auto body = [](const core::Mesh& m, const collision::Pose& p) {
    nlohmann::json hull = nlohmann::json::array();
    for (const auto& v : m.vertices()) hull.push_back(vec(v));
    const Eigen::Quaterniond q(p.rotation);
    return nlohmann::json{{"hull", hull}, {"position", vec(p.position)}, {"orientation", {q.w(), q.x(), q.y(), q.z()}}};
  };
  return {{"name", c.name}, {"a", body(*c.mesh_a, c.pose_a)}, {"b", body(*c.mesh_b, c.pose_b)}};
}

nlohmann::json random_corpus(std::uint64_t seed, int count) {
  const auto cases = collision::build_cases(collision::random_case_specs(seed, count), "random corpus");
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : cases) out.push_back(case_json(c));
  return out;
}

nlohmann::json collide(const std::vector<collision::CollisionCase>& cases, const CollideOptions& options) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t index = 0; index < cases.size(); ++index) {
    const auto& c = cases[index];
    const FclShape fa(*c.mesh_a), fb(*c.mesh_b);
    const BulletShape ba(*c.mesh_a), bb(*c.mesh_b);
    std::vector<collision::FeatureContact> trad_contacts, cga_contacts, pga_contacts, trad_manifold, cga_manifold,
        pga_manifold;
    traditional::Shape trad_a, trad_b;
    cga::Shape cga_a, cga_b;
    pga::Shape pga_a, pga_b;
    // Each method as a query; the referees' shapes are built once above, like
    // our meshes, so only the query is timed.
    const std::vector<std::function<PairContact()>> query{
        [&] {
          trad_contacts.clear();
          return traditional::narrowphase(c.a(), c.b(), collision::Method::report, &trad_contacts);
        },
        [&] {
          cga_contacts.clear();
          return cga::narrowphase(c.a(), c.b(), collision::Method::report, &cga_contacts);
        },
        [&] {
          pga_contacts.clear();
          return pga::narrowphase(c.a(), c.b(), collision::Method::report, &pga_contacts);
        },
        [&] { return first_meeting<traditional::Body>(trad_a, trad_b, c, trad_manifold); },
        [&] { return first_meeting<cga::Body>(cga_a, cga_b, c, cga_manifold); },
        [&] { return first_meeting<pga::Body>(pga_a, pga_b, c, pga_manifold); },
        [&] { return collision::sat_reference(c.a(), c.b()); },
        [&] { return fcl_collide(fa, c.pose_a, fb, c.pose_b); },
        [&] { return bullet_collide(ba, c.pose_a, bb, c.pose_b); },
    };
    const std::size_t n = query.size();
    std::vector<PairContact> result(n);
    std::vector<std::vector<double>> times(n);
    // A referee that gives no valid answer (Bullet's EPA on some deep overlaps,
    // compare/referee.hpp) is recorded as an error for that pair, not a crash.
    std::vector<std::string> error(n);
    for (int rep = 0; rep < options.repeat; ++rep)
      for (std::size_t k = 0; k < n; ++k) {  // interleaved, and the order turns each round
        const std::size_t m = (k + static_cast<std::size_t>(rep)) % n;
        if (!error[m].empty()) continue;
        try {
          const auto t0 = Clock::now();
          result[m] = query[m]();
          times[m].push_back(std::chrono::duration<double>(Clock::now() - t0).count());
        } catch (const Error& e) {
          error[m] = e.what();
        }
      }
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    const std::size_t reference = kReference;
    const PairContact& ref = result[reference];
    const bool touching = std::abs(ref.depth) <= collision::kTouchingBand * scale;
    nlohmann::json entry{{"name", c.name}, {"scale", scale}, {"touching", touching}};
    std::vector<std::string> disagree;
    for (std::size_t k = 0; k < n; ++k) {
      const std::string& method = collide_methods()[k];
      if (!error[k].empty()) {
        entry[method] = {{"error", error[k]}};
        if (!touching || our_method(method)) disagree.push_back(method);
        continue;
      }
      entry[method] = answer(result[k], spread(times[k]).median);
      if (k != reference && !touching && result[k].intersect != ref.intersect) disagree.push_back(method);
    }
    entry["traditional"]["contacts"] = trad_contacts.size();
    entry["cga"]["contacts"] = cga_contacts.size();
    entry["pga"]["contacts"] = pga_contacts.size();
    entry["traditional_manifold"]["contacts"] = trad_manifold.size();
    entry["cga_manifold"]["contacts"] = cga_manifold.size();
    entry["pga_manifold"]["contacts"] = pga_manifold.size();
    entry["disagree"] = disagree;
    if (!disagree.empty() && !options.disagreements.empty()) {
      std::filesystem::create_directories(options.disagreements);
      std::ostringstream name;
      name << std::setw(4) << std::setfill('0') << index << "-" << slug(c.name) << ".json";
      write_file_atomically(options.disagreements / name.str(), nlohmann::json::array({case_json(c)}).dump(1) + "\n");
    }
    out.push_back(entry);
  }
  return out;
}

std::string collide_table(const nlohmann::json& entries) {
  struct Acc {
    int compared = 0, agree = 0, overlapping = 0, errors = 0;
    std::vector<double> depth_err, angle, time, time_apart, time_overlapping;
  };
  std::map<std::string, Acc> acc;
  int touching = 0;
  for (const auto& e : entries) {
    if (e["touching"].get<bool>()) {
      ++touching;
      continue;
    }
    const auto& ref = e["sat"];
    const double scale = e["scale"];
    for (const auto& m : collide_methods()) {
      Acc& a = acc[m];
      const auto& r = e[m];
      ++a.compared;
      if (r.contains("error")) {
        ++a.errors;
        continue;
      }
      a.time.push_back(r["time_s"]);
      (ref["intersect"].get<bool>() ? a.time_overlapping : a.time_apart).push_back(r["time_s"]);
      a.agree += r["intersect"] == ref["intersect"];
      if (!(ref["intersect"].get<bool>() && r["intersect"].get<bool>())) continue;
      ++a.overlapping;
      a.depth_err.push_back(std::abs(r["depth"].get<double>() - ref["depth"].get<double>()) / scale);
      const Eigen::Vector3d n(r["normal"][0], r["normal"][1], r["normal"][2]);
      const Eigen::Vector3d nr(ref["normal"][0], ref["normal"][1], ref["normal"][2]);
      a.angle.push_back(std::atan2(n.cross(nr).norm(), n.dot(nr)));
    }
  }
  // The report's detector against its twin; everything else against what the
  // traditional simulation runs.
  const double t_report = spread(acc["traditional"].time).median;
  const double t_simulated = spread(acc["traditional_manifold"].time).median;
  std::ostringstream s;
  s << "| method | pairs | no answer | yes/no agree | depth error / scale, median (max) | normal angle rad, median (max) | "
       "time per pair, median µs | × traditional* | apart, median µs | overlapping, median µs |\n"
       "|---|---|---|---|---|---|---|---|---|---|\n";
  s << std::setprecision(3);
  for (const auto& m : collide_methods()) {
    const Acc& a = acc[m];
    const Spread d = spread(a.depth_err), g = spread(a.angle), t = spread(a.time);
    const double t_trad = m == "traditional" || m == "cga" || m == "pga" ? t_report : t_simulated;
    s << "| " << m << " | " << a.compared << " | " << a.errors << " | " << a.agree << " (" << (a.compared ? 100.0 * a.agree / a.compared : 0)
      << "%) | " << d.median << " (" << d.max << ") | " << g.median << " (" << g.max << ") | " << t.median * 1e6
      << " | " << (t_trad > 0 ? t.median / t_trad : 0) << " | " << spread(a.time_apart).median * 1e6 << " | "
      << spread(a.time_overlapping).median * 1e6 << " |\n";
  }
  s << "\n* traditional, cga and pga: × traditional (the report's detector, fig. 7, with the separating-axis depth); the "
       "rest: × traditional_manifold (what the simulation runs: the separating-axis test stopping at a separating "
       "axis, then the contact manifold).\n";
  s << "\n" << touching << " pair(s) inside the touching band (|reference depth| ≤ 1e-9 × scale) are not counted.\n";
  return s.str();
}

}  // namespace gacompare::compare
