#pragma once
// A test process's own folder under the system's temporary directory
// (`prefix` followed by the process id), removed when its tests end: ctest
// runs each test in a process of its own, and each left a folder behind.
// One prefix per test program: the first call fixes the folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <unistd.h>

namespace gacompare::testing {

inline std::filesystem::path process_folder(const std::string& prefix) {
  struct Remove : ::testing::Environment {
    std::filesystem::path root;
    explicit Remove(std::filesystem::path r) : root(std::move(r)) {}
    void TearDown() override {
      std::error_code ignored;
      std::filesystem::remove_all(root, ignored);
    }
  };
  // Registered on first use: gtest tears every environment down at the end,
  // the ones added while the tests ran included.
  static const std::filesystem::path root = [&] {
    auto r = std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()));
    ::testing::AddGlobalTestEnvironment(new Remove(r));
    return r;
  }();
  return root;
}

}  // namespace gacompare::testing
