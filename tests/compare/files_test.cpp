// compare/files.hpp: names from scene files as file names, whole-or-nothing
// writes and locked output folders.
#include "compare/files.hpp"

#include "core/error.hpp"
#include "core/model/sha256.hpp"

#include "../process_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;
using namespace gacompare::compare;

fs::path fresh(const std::string& name) {
  const fs::path d = gacompare::testing::process_folder("gacompare_files_") / name;
  fs::remove_all(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Ordinary names are kept; anything else is replaced, shortened and told
// apart by its SHA-256, so two names never share a folder and none is a path.
TEST(Files, NamesBecomeFileNames) {
  EXPECT_EQ(file_name_for("cube_drop_flat"), "cube_drop_flat");
  EXPECT_EQ(file_name_for("v1.2-a"), "v1.2-a");
  const std::string hostile = "../x`touch y`/$(z)";
  EXPECT_EQ(file_name_for(hostile), "_._x_touch_y____z_-" + gacompare::core::sha256_hex(hostile).substr(0, 8));
  EXPECT_NE(file_name_for("a b"), file_name_for("a_b"));  // the second is kept, the first is not
  EXPECT_EQ(file_name_for("a_b"), "a_b");
  EXPECT_EQ(file_name_for(".hidden").front(), '_');
  const std::string long_name(300, 'n');
  EXPECT_EQ(file_name_for(long_name), std::string(80, 'n') + "-" + gacompare::core::sha256_hex(long_name).substr(0, 8));
}

// A write replaces the file whole and leaves nothing beside it; one that fails
// says why and leaves nothing either.
TEST(Files, WritesAreWholeOrNothing) {
  const fs::path d = fresh("writes");
  write_file_atomically(d / "a.txt", "first");
  write_file_atomically(d / "a.txt", "second");
  EXPECT_EQ(slurp(d / "a.txt"), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  fs::create_directories(d / "b.txt");  // a folder where the file should go
  try {
    write_file_atomically(d / "b.txt", "x");
    FAIL() << "expected an error";
  } catch (const gacompare::Error& e) {
    EXPECT_EQ(e.kind(), gacompare::ErrorKind::run);
    EXPECT_NE(std::string(e.what()).find("b.txt: cannot rename"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 2);  // a.txt and the folder b.txt
}

// A write outside a locked folder (collide's --out and --table) removes the
// temporaries of the same file that a killed writer left (its PID no longer
// runs), and leaves a live writer's, this process's and other files' alone.
TEST(Files, AWriteRemovesWhatADeadWriterOfItLeft) {
  const fs::path d = fresh("dead_writer");
  fs::create_directories(d);
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // its PID now names no process
  const std::string dead = std::to_string(child), self = std::to_string(::getpid());
  for (const std::string& name : {".t.md." + dead + "-1.tmp", ".t.md." + self + "-7.tmp", std::string(".t.md.1-0.tmp"),
                                  ".t.md.x." + dead + "-1.tmp", ".other.md." + dead + "-0.tmp"})
    std::ofstream(d / name) << "half";
  write_file_atomically(d / "t.md", "whole\n");
  EXPECT_FALSE(fs::exists(d / (".t.md." + dead + "-1.tmp")));
  EXPECT_TRUE(fs::exists(d / (".t.md." + self + "-7.tmp")));  // this process's own
  EXPECT_TRUE(fs::exists(d / ".t.md.1-0.tmp"));               // PID 1 runs
  EXPECT_TRUE(fs::exists(d / (".t.md.x." + dead + "-1.tmp")));  // another file's (t.md.x)
  EXPECT_TRUE(fs::exists(d / (".other.md." + dead + "-0.tmp")));
  EXPECT_EQ(slurp(d / "t.md"), "whole\n");
}

// A folder is held by one lock at a time (flock: a second open file
// description is refused, in this process as in another); the lock removes
// what a killed run left, and the folder it made when nothing was written.
TEST(Files, AFolderHasOneWriter) {
  const fs::path d = fresh("lock");
  {
    const FolderLock first(d);
    try {
      const FolderLock second(d);
      FAIL() << "a second lock was granted";
    } catch (const gacompare::Error& e) {
      EXPECT_EQ(e.kind(), gacompare::ErrorKind::input);
      EXPECT_EQ(std::string(e.what()), d.string() + ": another gacompare is writing this folder; wait for it to finish or give another --out");
    }
  }
  EXPECT_FALSE(fs::exists(d)) << "the empty folder the lock made is left";
  fs::create_directories(d / "scene");
  std::ofstream(d / ".results.json.123-0.tmp") << "half";
  std::ofstream(d / "scene" / ".report.md.123-1.tmp") << "half";
  std::ofstream(d / "kept.json") << "{}";
  std::ofstream(d / ".someone_elses.tmp") << "theirs";  // --out may hold other files: only ours go
  std::ofstream(d / ".a.b-c.tmp") << "theirs";
  { const FolderLock again(d); }
  EXPECT_FALSE(fs::exists(d / ".results.json.123-0.tmp"));
  EXPECT_FALSE(fs::exists(d / "scene" / ".report.md.123-1.tmp"));
  EXPECT_TRUE(fs::exists(d / "kept.json"));
  EXPECT_TRUE(fs::exists(d / ".someone_elses.tmp"));
  EXPECT_TRUE(fs::exists(d / ".a.b-c.tmp"));
}

}  // namespace
