#pragma once
// Running the gacompare binary from a test: exit code, stdout and stderr, in a
// per-process scratch folder. Shared by cli_test.cpp and collide_test.cpp.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct Result {
  int code;
  std::string out, err;
};

// This process's scratch folder, removed when the test binary exits.
const fs::path& scratch() {
  struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("gacompare_cli_" + std::to_string(::getpid()));
    ~Scratch() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  };
  static const Scratch s;
  return s.dir;
}

// Runs gacompare with `args`; stdout and stderr captured separately.
[[maybe_unused]] Result gacompare(const std::string& args) {
  const fs::path dir = scratch();
  fs::create_directories(dir);
  const std::string cmd = std::string(GACOMPARE_BIN) + " " + args + " >" + (dir / "out").string() + " 2>" +
                          (dir / "err").string();
  const int status = std::system(cmd.c_str());
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "out"), slurp(dir / "err")};
}

[[maybe_unused]] fs::path fresh_dir(const std::string& name) {
  const fs::path d = scratch() / name;
  fs::remove_all(d);
  return d;
}

[[maybe_unused]] void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// A scene that runs in milliseconds.
const std::string kScene = std::string(GACOMPARE_DATA_DIR) + "/scenes/projectile_linear_drag.json";

[[maybe_unused]] json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

}  // namespace
