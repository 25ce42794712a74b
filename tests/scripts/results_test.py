#!/usr/bin/env python3
"""scripts/results.py's machinery and scripts/check-docs.py's anchors, against
hand-written inputs whose answers are known (ctest -L docs)."""
import importlib.util
import os
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from resultgen import common, contacts, dynamics, stacking, summary  # noqa: E402

spec = importlib.util.spec_from_file_location("check_docs", os.path.join(ROOT, "scripts", "check-docs.py"))
check_docs = importlib.util.module_from_spec(spec)
spec.loader.exec_module(check_docs)


class Fill(unittest.TestCase):
    PAGE = ("# T\n\n<!-- generated: a -->\nold a\n<!-- end: a -->\n\nprose\n\n"
            "<!-- generated: b -->\nold b\n<!-- end: b -->\n")

    def test_replaces_the_named_blocks_and_keeps_the_rest(self):
        out = common.fill(self.PAGE, {"a": "new a"}, "page")
        self.assertIn("<!-- generated: a -->\nnew a\n<!-- end: a -->", out)
        self.assertIn("<!-- generated: b -->\nold b\n<!-- end: b -->", out)
        self.assertIn("\nprose\n", out)

    def test_a_block_the_page_lacks_is_refused(self):
        with self.assertRaises(SystemExit) as e:
            common.fill(self.PAGE, {"c": "x"}, "page")
        self.assertIn("no block c", str(e.exception))

    def test_filling_twice_gives_the_same_page(self):
        once = common.fill(self.PAGE, {"a": "x", "b": "y"}, "page")
        self.assertEqual(once, common.fill(once, {"a": "x", "b": "y"}, "page"))


class Pyramids(unittest.TestCase):
    TABLE = ("| layers | cubes | backend | s per simulated s | contacts per step | factorisations per step | "
             "active-set changes | farthest from rest (m) |\n|---:|---:|---|---:|---:|---:|---:|---:|\n"
             "| 3 | 14 | traditional | 0.066 (0.066–0.066) | 110 | 0.263 | 14 | 0.0001 |\n"
             "| 3 | 14 | bullet | 0.123 (0.123–0.123) | – | – | – | 9.7e-06 |\n"
             "| 10 | 385 | traditional | 8 (7–9) | 4.62e+03 | 1.33 | 341 | 0.00027 |\n"
             "| 10 | 385 | cga | 6 (6–6) | 4.62e+03 | 1.34 | 387 | 0.00027 |\n"
             "| 10 | 385 | bullet | 4 (4–4) | – | – | – | 0.00014 |\n"
             "| 15 | 1240 | traditional | 150 (150–150) | 1.59e+04 | 3.36 | 1950 | 0.00038 |\n")

    def test_ratios_to_bullet_for_the_pyramids_of_a_hundred_cubes_or_more(self):
        # 14 cubes is below the cut, and 1,240 cubes has no Bullet run to divide by.
        [row] = stacking.pyramids_against_bullet(self.TABLE)
        self.assertEqual(row["value"], "385 cubes: traditional 2.00×, cga 1.50×")
        self.assertEqual(row["anchor"], "#stacks-at-scale")


class Tables(unittest.TestCase):
    def test_rows_without_the_rule_line(self):
        md = "text\n\n| a | b |\n|---|---:|\n| 1 | 2 |\n| 3 | 4 |\n\nafter\n\n| c |\n|---|\n| 5 |\n"
        self.assertEqual(common.tables(md), [[["a", "b"], ["1", "2"], ["3", "4"]], [["c"], ["5"]]])

    def test_ratio_of_reads_the_median_cell(self):
        md = "| operation | implementation | ns per op | ratio to matrix |\n|---|---|---:|---:|\n" \
             "| derivative | matrix | 18.3 (18.0–19.0) | 1.00 (1.00–1.00) |\n" \
             "| derivative | rotor | 18.8 (18.6–19.3) | 1.02 (0.99–1.06) |\n"
        self.assertEqual(common.ratio_of(md, "derivative", "rotor"), "1.02 (0.99–1.06)")
        self.assertIsNone(common.ratio_of(md, "step", "rotor"))

    def test_first_number(self):
        self.assertEqual(common.first_number("1.5e-03 (rel 2)"), 1.5e-3)
        self.assertIsNone(common.first_number("–"))


class ContactFamilies(unittest.TestCase):
    TABLE = ("| case | traditional | cga | bullet |\n|---|---|---|---|\n"
             "| slide/equal/free/turn=none/offset=none (contact_slide) | pass 1e-13 m/s | pass 1e-13 m/s | FAIL 0.1 m/s |\n"
             "| slide/equal/floor/turn=none/offset=none | pass 1e-13 m/s | FAIL 1 m/s | FAIL 0.2 m/s |\n"
             "| row/5 | pass 1e-13 | pass 1e-13 | pass 1e-12 |\n"
             "| stack/5/drop=1mm | pass 1e-8 m | pass 1e-8 m | FAIL 0.1 m |\n")

    def test_counts_per_family_and_backend(self):
        counts, backends = contacts.counts(self.TABLE)
        self.assertEqual(backends, ["traditional", "cga", "bullet"])
        self.assertEqual(counts["slides, free"], {"traditional": [1, 1], "cga": [1, 1], "bullet": [0, 1]})
        self.assertEqual(counts["slides on a floor"]["cga"], [0, 1])
        self.assertEqual(counts["rows"]["bullet"], [1, 1])
        self.assertEqual(counts["stacks"]["bullet"], [0, 1])

    def test_the_total_row(self):
        _, total, cases = contacts.family_table(self.TABLE, self.TABLE)
        self.assertEqual(cases, 4)
        self.assertEqual(total, {"traditional": [4, 4], "cga": [3, 4], "bullet": [1, 4]})


class EqualAccuracy(unittest.TestCase):
    MD = ("### spinning_top\n\n#### Time at equal accuracy\n\n"
          "| backend | setting | time / traditional | time / traditional-quaternion |\n|---|---|---:|---:|\n"
          "| traditional | tol 1e-9 | 1 | 1.40 (1.3–1.5) |\n| traditional-quaternion | tol 8e-9 | 0.71 (0.7–0.8) | 1 |\n"
          "| cga | tol 8e-9 | 0.46 (0.40–0.50) | 0.98 (0.95–1.02) |\n\n"
          "### dzhanibekov\n\n#### Time at equal accuracy\n\n| backend | setting | time / traditional |\n|---|---|---:|\n"
          "| traditional | tol 3e-12 | 1 |\n| cga | tol 1e-11 | 0.68 (0.65–0.75) |\n")

    def test_each_scene_reads_its_own_table(self):
        self.assertEqual(dynamics._accuracy_ratio(self.MD, "spinning_top"), "0.46 (0.40–0.50)")
        self.assertEqual(dynamics._accuracy_ratio(self.MD, "spinning_top", "cga", "traditional-quaternion"),
                         "0.98 (0.95–1.02)")
        self.assertIsNone(dynamics._accuracy_ratio(self.MD, "dzhanibekov", "cga", "traditional-quaternion"))
        self.assertEqual(dynamics._accuracy_ratio(self.MD, "dzhanibekov"), "0.68 (0.65–0.75)")
        self.assertIsNone(dynamics._accuracy_ratio(self.MD, "kepler"))


def _category(ratio, lo, hi, verdict, scenes):
    """One category of summary.json, its overall numbers only."""
    return {"evidence": True, "scenes": scenes,
            "overall": {"ratio": ratio, "ci95": [lo, hi], "verdict": verdict, "scenes": len(scenes)}}


class SummaryPairs(unittest.TestCase):
    """summary.json as gacompare writes it: cga / traditional at the top level,
    the other pairs that ran under "pairs", each of the same shape."""
    SUMMARY = {
        "scenes": [{"name": "drag", "category": "particles", "trajectories": "identical"},
                   {"name": "box", "category": "rigid bodies", "trajectories": "within tolerance"}],
        "categories": {"rigid bodies": _category(0.77, 0.76, 0.78, "cga faster", ["box"]),
                       "particles": _category(1.0, 0.99, 1.01, "within noise", ["drag"])},
        "pairs": [{"numerator": "pga", "denominator": "traditional", "scenes": [],
                   "categories": {"rigid bodies": _category(1.2, 1.1, 1.3, "pga slower", ["box"])}},
                  {"numerator": "pga", "denominator": "cga", "scenes": [],
                   "categories": {"rigid bodies": _category(1.5, None, None, "no verdict", ["box"])}}],
    }

    def test_every_pair_in_order(self):
        self.assertEqual([f"{n} / {d}" for n, d, _ in summary.pairs(self.SUMMARY)],
                         ["cga / traditional", "pga / traditional", "pga / cga"])

    def test_a_headline_on_bodies_names_the_representations(self):
        """Scenes that carry "rotation" name each side's form; the quaternion
        twin reads as the traditional backend with its form."""
        box = {"name": "box", "category": "rigid bodies", "trajectories": "within tolerance",
               "rotation": {"traditional-quaternion": "quaternion", "cga": "rotor"}}
        block = {"scenes": [box], "categories": {"rigid bodies": _category(0.96, 0.93, 1.01, "within noise", ["box"])}}
        self.assertEqual(summary.label("cga", "traditional-quaternion", block, "rigid bodies"),
                         "cga (rotor) / traditional (quaternion)")
        self.assertEqual(summary.label("cga", "traditional-quaternion", block, "collisions"),
                         "cga / traditional-quaternion")

    def test_parted_scenes_are_named_as_left_out(self):
        """A category's ratio leaves its parted scenes out, and the headline
        says which; with every scene parted there is no verdict."""
        block = {"scenes": [], "categories": {"collisions": dict(
            _category(1.02, 1.0, 1.04, "cga slower", ["drop"]), parted=["box", "pile"])}}
        self.assertEqual(summary.overall(block, "collisions"),
                         "1.02 [1.00, 1.04], cga slower (1 scenes; box and pile parted, left out)")
        block["categories"]["collisions"] = {"evidence": True, "scenes": [], "parted": ["box"],
                                             "overall": {"ratio": None, "ci95": [None, None],
                                                         "verdict": "no verdict", "scenes": 0}}
        self.assertEqual(summary.overall(block, "collisions"), "no verdict: every scene parted; box parted, left out")

    def test_a_headline_row_per_pair_and_category(self):
        rows = summary.headline(self.SUMMARY)
        self.assertEqual([(r["finding"], r["value"]) for r in rows], [
            ("Rigid bodies without contact: whole run, cga / traditional at equal tolerance",
             "0.77 [0.76, 0.78], cga faster (1 scenes)"),
            ("Rigid bodies without contact: whole run, pga / traditional at equal tolerance",
             "1.20 [1.10, 1.30], pga slower (1 scenes)"),
            ("Rigid bodies without contact: whole run, pga / cga at equal tolerance", "1.50, no verdict (1 scenes)"),
            ("Particle scenes (the same formulas in every backend)",
             "identical trajectories on 1 of 1; 1.00 [0.99, 1.01], within noise (1 scenes)"),
        ])

    def test_a_summary_without_pairs_reads_as_before(self):
        old = {k: v for k, v in self.SUMMARY.items() if k != "pairs"}
        self.assertEqual(len(summary.headline(old)), 2)


class Anchors(unittest.TestCase):
    def test_github_slugs(self):
        self.assertEqual(check_docs.slug("compare --accuracy: time at equal accuracy"),
                         "compare---accuracy-time-at-equal-accuracy")
        self.assertEqual(check_docs.slug("The algebra (`cga/algebra/`)"), "the-algebra-cgaalgebra")
        self.assertEqual(check_docs.slug("Rigid bodies (§2.3)"), "rigid-bodies-23")
        self.assertEqual(check_docs.slug("[Link](x.md) here"), "link-here")

    def test_repeated_headings_are_numbered_and_fences_skipped(self):
        text = "# A\n## A\n```\n# not a heading\n```\n## B\n"
        self.assertEqual(check_docs.anchors(text), {"a", "a-1", "b"})

    def test_named_paths_but_not_patterns(self):
        found = [m.group(1) for m in check_docs.NAMED_PATH.finditer(
            "`core/scene.hpp`, `data/scenes/*.json`, `tests/{traditional,cga}/x.cpp`, `cga/algebra/` and `build/ci`")]
        self.assertEqual(found, ["core/scene.hpp", "cga/algebra/"])

    def test_a_commit_hash_is_found_and_a_word_is_not(self):
        self.assertTrue(check_docs.HASH.search("regenerated at c9972dd today"))
        self.assertFalse(check_docs.HASH.search("the folder x__touch_y_-fb2e581c and deadbeef"))


if __name__ == "__main__":
    unittest.main()
