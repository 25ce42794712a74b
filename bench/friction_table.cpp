// The friction table (docs/results/contacts.md): each friction scene
// (data/scenes/friction_*.json) through traditional, cga, pga and Bullet, each
// figure against its analytic answer (answers/friction_answers.hpp). A cell is the
// measured value and its error (relative, or absolute in the unit where the
// answer is 0). Markdown on stdout.
//
//   build/release/bench/friction_table [scene.json ...]
//
// Without arguments: the three bundled friction scenes, the rolling spheres,
// the top on the floor and the mixed pile (answers/friction_answers.hpp).
#include "core/memory.hpp"
#include "compare/runner.hpp"
#include "core/error.hpp"
#include "answers/friction_answers.hpp"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

using namespace gacompare;

int main(int argc, char** argv) {
  gacompare::core::keep_freed_memory();  // core/memory.hpp: a stack's solves no longer shrink and regrow the heap
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) files.emplace_back(argv[i]);
  if (files.empty())
    for (const char* name : {"friction_incline_stick", "friction_incline_slide", "friction_floor_stop", "sphere_roll_incline",
                             "sphere_slide_to_roll", "top_on_floor", "mixed_pile"})
      files.push_back(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (std::string(name) + ".json"));
  try {
    std::printf("| scene | figure | analytic | traditional | cga | pga | Bullet |\n|---|---|---|---|---|---|---|\n");
    for (const auto& file : files) {
      const core::Scene scene = core::load_scene(file);
      std::vector<core::Run> runs;
      for (const char* backend : {"traditional", "cga", "pga", "bullet"}) runs.push_back(compare::run_backend(scene, backend));
      std::vector<std::vector<core::FrictionFigure>> figures;
      for (const auto& run : runs) {
        if (run.error) throw std::runtime_error(scene.name + " (" + run.backend + "): " + *run.error);
        figures.push_back(core::analytic_figures(scene, run));
      }
      for (std::size_t k = 0; k < figures[0].size(); ++k) {
        const auto& f = figures[0][k];
        std::printf("| %s | %s (%s) | %.7g |", scene.name.c_str(), f.quantity.c_str(), f.unit.c_str(), f.analytic);
        for (const auto& of : figures)
          std::printf(" %.7g (%s %.1e) |", of[k].measured, f.analytic == 0 ? "abs" : "rel", of[k].error());
        std::printf("\n");
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "friction_table: %s\n", e.what());
    return 1;
  }
}
