// core/read_file.hpp: the one way an input file is read. Regular files only,
// each other kind refused by name before it is opened (a FIFO would block, a
// device never end), links refused unless the user named the path, and a size
// limit that holds even for a file whose size reads 0.
#include "core/read_file.hpp"

#include "core/error.hpp"

#include "../process_folder.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;
using namespace gacompare;
using core::Links;
using core::read_file;

fs::path fresh(const std::string& name) {
  const fs::path d = gacompare::testing::process_folder("gacompare_read_file_") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string refusal(const fs::path& p, Links links = Links::refuse) {
  try {
    read_file(p, "scene file", links);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    return e.what();
  }
  return "read";
}

TEST(ReadFile, ReadsARegularFileWhole) {
  const fs::path d = fresh("regular");
  std::string text(200000, 'x');
  text[7] = '\0';  // bytes, not a C string
  std::ofstream(d / "a.json", std::ios::binary) << text;
  EXPECT_EQ(read_file(d / "a.json", "scene file"), text);
  std::ofstream(d / "empty.json").close();
  EXPECT_EQ(read_file(d / "empty.json", "scene file"), "");
}

TEST(ReadFile, EveryOtherKindIsRefusedAtOnce) {
  const fs::path d = fresh("kinds");
  ASSERT_EQ(::mkfifo((d / "fifo").c_str(), 0600), 0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(refusal(d / "fifo"), (d / "fifo").string() + ": expected a scene file, got a FIFO (named pipe)");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);  // not waited on
  EXPECT_EQ(refusal("/dev/zero", Links::follow), "/dev/zero: expected a scene file, got a character device");
  EXPECT_EQ(refusal(d), d.string() + ": expected a scene file, got a directory");
  EXPECT_EQ(refusal(d / "none"), (d / "none").string() + ": cannot open the scene file: No such file or directory");
}

TEST(ReadFile, LinksAreFollowedOnlyWhereTheUserNamedThePath) {
  const fs::path d = fresh("links");
  std::ofstream(d / "real.json") << "{}";
  fs::create_symlink(d / "real.json", d / "link.json");
  EXPECT_NE(refusal(d / "link.json").find(": expected a scene file, got a symbolic link (not followed"), std::string::npos);
  EXPECT_EQ(read_file(d / "link.json", "scene file", Links::follow), "{}");
  fs::create_symlink("/dev/zero", d / "zero.json");  // followed, it is still a device
  EXPECT_EQ(refusal(d / "zero.json", Links::follow), (d / "zero.json").string() + ": expected a scene file, got a character device");
}

TEST(ReadFile, TheSizeLimitHoldsAndIsStated) {
  const fs::path d = fresh("size");
  std::ofstream(d / "ten") << "0123456789";
  std::ofstream(d / "eleven") << "0123456789a";
  core::set_max_input_bytes(10);
  EXPECT_EQ(read_file(d / "ten", "scene file"), "0123456789");
  EXPECT_EQ(refusal(d / "eleven"),
            (d / "eleven").string() + ": the scene file is 1.1e-05 MB, above the limit of 1e-05 MB (--max-input-mb raises it)");
  // A kernel file's size reads 0: the read itself stops past the limit.
  EXPECT_NE(refusal("/proc/self/status", Links::follow).find("is more than 1e-05 MB, above the limit"), std::string::npos);
  core::set_max_input_bytes(core::kDefaultMaxInputBytes);
  EXPECT_FALSE(read_file("/proc/self/status", "status", Links::follow).empty());
}

TEST(ReadFile, MessagesAreOneLineOfUtf8) {
  EXPECT_EQ(core::one_line("a\nb\tc\x7f"), "a b c ");
  EXPECT_EQ(core::one_line("caf\xc3\xa9 \xff!"), "caf\xc3\xa9 ?!");
}

}  // namespace
