#pragma once
// The gacompare binary run as a user would, for the `reliability` tests: each
// run in a fresh folder (in/ its inputs, out/ its --out, tmp/ its TMPDIR), its
// exit code and one line checked, nothing written outside --out. Shared by
// reliability_test.cpp and reliability_inputs_test.cpp.
#include "cli_run.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace {

const fs::path kScenes = fs::path(GACOMPARE_DATA_DIR) / "scenes";
const fs::path kMeshes = fs::path(GACOMPARE_DATA_DIR).parent_path() / "tests" / "core" / "data" / "meshes";

[[maybe_unused]] std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

[[maybe_unused]] json bundled(const std::string& name) { return read_json(kScenes / (name + ".json")); }

// Shell-quoted for sh -c: the only way to pass a path with anything in it.
[[maybe_unused]] std::string sh(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// One test's folder: in/ (its scenes), out/ (its --out), tmp/ (its TMPDIR);
// gacompare runs with the folder as its working directory, so a default
// output folder or a stray file lands here, where strays() finds it.
struct Work {
  fs::path root;
  explicit Work(const std::string& name) : root(scratch() / ("reliability_" + name)) {
    fs::remove_all(root);
    fs::create_directories(root / "in");
    fs::create_directories(root / "tmp");
  }
  fs::path out() const { return root / "out"; }
  fs::path marker() const { return root / "PWNED"; }  // what a name that ran `touch PWNED` would make
  fs::path scene(const std::string& file, const json& j) const {
    const fs::path p = root / "in" / file;
    std::ofstream(p) << j.dump();
    return p;
  }
  std::string command(const std::string& args, const std::string& prefix = "") const {
    return prefix + "cd " + sh(root.string()) + " && TMPDIR=" + sh((root / "tmp").string()) + " exec " +
           std::string(GACOMPARE_BIN) + " " + args + " >" + sh((root.string() + ".out")) + " 2>" +
           sh((root.string() + ".err"));
  }
  Result run(const std::string& args, const std::string& prefix = "") const {
    const int status = std::system(("sh -c " + sh(command(args, prefix))).c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(root.string() + ".out"), slurp(root.string() + ".err")};
  }
  // Everything written outside in/ and out/ (the marker, a default folder, a
  // plot folder in tmp/).
  std::vector<std::string> strays() const {
    std::vector<std::string> found;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      const fs::path rel = fs::relative(e.path(), root);
      const std::string top = rel.begin()->string();
      if (top == "in" || top == "out" || rel == "tmp") continue;
      found.push_back(rel.string());
    }
    return found;
  }
};

// Exit `code` with exactly one line on stderr, "gacompare: ...", holding each of `parts`.
[[maybe_unused]] void expect_one_line(const Result& r, int code, const std::vector<std::string>& parts) {
  EXPECT_EQ(r.code, code) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("gacompare: ", 0), 0u) << r.err;
  for (const auto& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << "no '" << p << "' in " << r.err;
}

[[maybe_unused]] void expect_clean(const Work& w) {
  EXPECT_FALSE(fs::exists(w.marker())) << "a name ran a command";
  EXPECT_TRUE(w.strays().empty()) << "written outside --out: " << w.strays().front();
}

// A refused scene: exit 2, one line naming the file and the JSON path.
[[maybe_unused]] void expect_refused(const std::string& test, const json& scene, const std::vector<std::string>& parts,
                    const std::string& flags = "") {
  const Work w(test);
  const fs::path file = w.scene("s.json", scene);
  const Result r = w.run(flags + "run " + sh(file.string()) + " --backend traditional --quiet --out out");
  std::vector<std::string> all{file.string() + ": "};
  all.insert(all.end(), parts.begin(), parts.end());
  expect_one_line(r, 2, all);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(w.out())) << "a refused run left its output folder";
  expect_clean(w);
}

}  // namespace
