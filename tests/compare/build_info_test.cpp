// compare/build_info.cmake, the build step that records the commit and whether
// the tree was dirty, run on a scratch git repository in each state it must
// tell apart (git itself is the independent answer).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;

const fs::path& scratch() {
  static const fs::path dir = fs::temp_directory_path() / ("gacompare_build_info_" + std::to_string(::getpid()));
  return dir;
}

int sh(const std::string& cmd) { return std::system((cmd + " > /dev/null 2>&1").c_str()); }

// The {commit, dirty} pair the script writes for `repo`.
std::string recorded(const fs::path& repo) {
  const fs::path out = scratch() / "build_info.cpp";
  fs::remove(out);
  EXPECT_EQ(sh(std::string(GACOMPARE_CMAKE) + " -DSOURCE_DIR=" + repo.string() + " -DOUT=" + out.string() + " -P " +
               GACOMPARE_BUILD_INFO_SCRIPT),
            0);
  std::ifstream in(out);
  std::stringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  const auto at = text.find("return {");
  return at == std::string::npos ? text : text.substr(at + 8, text.find('}', at) - at - 8);
}

std::string head(const fs::path& repo) {
  FILE* p = ::popen(("git -C " + repo.string() + " rev-parse HEAD").c_str(), "r");
  char buf[64] = {0};
  if (!p || !std::fgets(buf, sizeof buf, p)) return "";
  ::pclose(p);
  return std::string(buf, 40);
}

}  // namespace

TEST(BuildInfo, CommitAndDirtyAsGitSeesThem) {
  ASSERT_EQ(std::system("command -v git > /dev/null"), 0) << "git not found (scripts/install-deps.sh installs it)";
  const fs::path repo = scratch() / "repo";
  fs::remove_all(scratch());
  fs::create_directories(repo);
  EXPECT_EQ(recorded(repo), "\"unknown\", \"unknown\"");  // not a repository (a tarball)

  const std::string git = "git -C " + repo.string() + " -c user.name=t -c user.email=t@t ";
  ASSERT_EQ(sh(git + "init -q"), 0);
  std::ofstream(repo / "a.cpp") << "int a;\n";
  std::ofstream(repo / ".gitignore") << "build/\n";
  ASSERT_EQ(sh(git + "add a.cpp .gitignore"), 0);
  ASSERT_EQ(sh(git + "commit -q -m one"), 0);
  const std::string commit = head(repo);
  ASSERT_EQ(commit.size(), 40u);
  EXPECT_EQ(recorded(repo), "\"" + commit + "\", \"no\"");

  fs::create_directories(repo / "build");  // ignored: the build folder itself
  std::ofstream(repo / "build" / "x.o") << "x";
  EXPECT_EQ(recorded(repo), "\"" + commit + "\", \"no\"");

  std::ofstream(repo / "a.cpp") << "int a = 1;\n";  // a tracked file edited
  EXPECT_EQ(recorded(repo), "\"" + commit + "\", \"yes\"");
  ASSERT_EQ(sh(git + "checkout -q a.cpp"), 0);
  EXPECT_EQ(recorded(repo), "\"" + commit + "\", \"no\"");

  std::ofstream(repo / "b.cpp") << "int b;\n";  // a new file not yet added
  EXPECT_EQ(recorded(repo), "\"" + commit + "\", \"yes\"");
  ASSERT_EQ(sh(git + "add b.cpp"), 0);          // staged, not committed
  EXPECT_EQ(recorded(repo), "\"" + commit + "\", \"yes\"");
  fs::remove_all(scratch());
}
