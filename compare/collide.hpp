#pragma once
// `gacompare collide CASES.json...`: every pair through the two
// backends' narrowphases (the report's detector, with the separating-axis fast
// path for depth and normal), the exact separating-axis reference, FCL and
// Bullet; one JSON entry per pair, the agreement table, and the disagreements
// written as replayable case files.
#include "answers/collision_cases.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace gacompare::compare {

// The methods, in the table's order: our three backends with the report's
// detector (fig. 7) and with what the simulation runs (the separating-axis
// test stopping at a separating axis, then the contact manifold:
// sat_then_manifold), the exact reference, the referees.
inline const std::vector<std::string>& collide_methods() {
  static const std::vector<std::string> m{"traditional", "cga", "pga", "traditional_manifold", "cga_manifold",
                                          "pga_manifold", "sat", "fcl", "bullet"};
  return m;
}
// Ours (a disagreement with the reference fails `gacompare collide`).
inline bool our_method(const std::string& m) {
  return m.rfind("traditional", 0) == 0 || m.rfind("cga", 0) == 0 || m.rfind("pga", 0) == 0;
}

struct CollideOptions {
  int repeat = 5;                     // timed queries per method and pair (interleaved); the median is reported
  std::filesystem::path disagreements;  // where to write replayable cases; empty: don't
};

// One entry per case: {"name", "scale", "touching", and per method {"intersect",
// "depth", "normal", "contact", "feature", "time_s"} (+ "contacts" for our
// methods: how many feature contacts the report's detector or the manifold
// found)}. The manifold methods are timed as the simulation meets a pair for
// the first time: both bodies' geometry built (in storage kept from query to
// query, as the simulation keeps it), no axis remembered from before.
nlohmann::json collide(const std::vector<collision::CollisionCase>& cases, const CollideOptions& options);

// The agreement and timing table (markdown) over collide()'s entries: per
// method, yes/no agreement with the reference outside the touching band, depth
// error and normal angle against it on overlapping pairs, median time per pair.
std::string collide_table(const nlohmann::json& entries);

// A case written back in the input format (hulls of the meshes' vertices, in
// body coordinates), so `gacompare collide` replays it.
nlohmann::json case_json(const collision::CollisionCase& c);

// The random corpus as a case file (collision::random_case_specs).
nlohmann::json random_corpus(std::uint64_t seed, int count);

}  // namespace gacompare::compare
