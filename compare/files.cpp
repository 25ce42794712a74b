#include "compare/files.hpp"

#include "core/error.hpp"
#include "core/model/sha256.hpp"

#include <algorithm>
#include <cstdio>
#include <set>
#include <atomic>
#include <optional>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <csignal>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gacompare::compare {

namespace fs = std::filesystem;

namespace {

std::string reason(int error) { return std::strerror(error); }

// .NAME.PID-N.tmp beside the file: unique to this process and call.
fs::path temporary_for(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  // Appended piece by piece: GCC 12's "." + string trips a false -Wrestrict (bug 105651).
  std::string name = ".";
  name += path.filename().string();
  name += '.';
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter++);
  name += ".tmp";
  return path.parent_path() / name;
}

// What temporary_for made, read back from a name: the file it stands for
// (NAME) and the writer's PID.
struct Temporary {
  std::string file;
  pid_t pid;
};

// Exactly what temporary_for makes, .NAME.PID-N.tmp, and nothing else of the
// user's: --out may be a folder that holds other files.
std::optional<Temporary> temporary_of(const fs::path& p) {
  const std::string name = p.filename().string();
  if (name.size() < 9 || name.front() != '.' || name.compare(name.size() - 4, 4, ".tmp") != 0) return std::nullopt;
  const std::string middle = name.substr(0, name.size() - 4);  // .NAME.PID-N
  const auto dash = middle.rfind('-'), dot = middle.rfind('.', dash == std::string::npos ? 0 : dash);
  if (dash == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 >= dash || dash + 1 >= middle.size())
    return std::nullopt;
  const auto digits = [&](std::size_t a, std::size_t b) {
    return std::all_of(middle.begin() + static_cast<std::ptrdiff_t>(a), middle.begin() + static_cast<std::ptrdiff_t>(b),
                       [](char c) { return c >= '0' && c <= '9'; });
  };
  if (!digits(dot + 1, dash) || !digits(dash + 1, middle.size())) return std::nullopt;
  // A PID longer than any pid_t holds names no process (and would overflow).
  const std::string pid = middle.substr(dot + 1, dash - dot - 1);
  return Temporary{middle.substr(1, dot - 1), pid.size() > 9 ? pid_t{-1} : static_cast<pid_t>(std::stol(pid))};
}

bool is_temporary(const fs::path& p) { return temporary_of(p).has_value(); }

// What a killed run left: .NAME*.tmp files in the folder and the folders below
// it (a compare of several scenes writes one folder per scene, a sweep cells/).
void remove_temporaries(const fs::path& dir, int depth) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const auto status = it->symlink_status(ec);
    if (ec) break;
    if (fs::is_regular_file(status) && is_temporary(it->path())) fs::remove(it->path(), ec);
    else if (fs::is_directory(status) && depth > 0) remove_temporaries(it->path(), depth - 1);
  }
}

// The temporaries of `path` that a killed writer left (.NAME.PID-N.tmp with
// a PID that no longer runs): a command that writes files outside a locked
// output folder (collide's --out and --table) would otherwise keep them for
// ever. A live writer's, and this process's, are left alone.
void remove_dead_temporaries_of(const fs::path& path) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const std::string file = path.filename().string();
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::optional<Temporary> t = temporary_of(it->path());
    if (!t || t->file != file || t->pid == ::getpid()) continue;
    if (t->pid > 0 && (::kill(t->pid, 0) == 0 || errno != ESRCH)) continue;
    if (!fs::is_regular_file(it->symlink_status(ec))) continue;
    fs::remove(it->path(), ec);
  }
}

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& text) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw run_error(dir.string() + ": cannot create folder: " + ec.message());
  // An anonymous file: nothing anyone can see until it is complete.
  int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  fs::path named;  // its temporary name, once it has one
  if (fd < 0) {
    if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL)
      throw run_error(path.string() + ": cannot write: " + reason(errno));
    named = temporary_for(path);
    fd = ::open(named.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) throw run_error(path.string() + ": cannot write: " + reason(errno));
  }
  const auto fail = [&](const std::string& what, int error) {
    if (fd >= 0) ::close(fd);
    if (!named.empty()) ::unlink(named.c_str());
    throw run_error(path.string() + ": " + what + ": " + reason(error));
  };
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("cannot write", errno);
    done += static_cast<std::size_t>(n);
  }
  if (named.empty()) {
    named = temporary_for(path);
    const std::string self = "/proc/self/fd/" + std::to_string(fd);
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, named.c_str(), AT_SYMLINK_FOLLOW) != 0) {
      const int error = errno;
      named.clear();  // nothing was created
      fail("cannot write", error);
    }
  }
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) fail("cannot write", errno);  // a delayed write error (NFS, a full disk)
  if (::rename(named.c_str(), path.c_str()) != 0) fail("cannot rename " + named.string() + " to it", errno);
  remove_dead_temporaries_of(path);
}

std::string file_name_for(const std::string& name) {
  std::string out;
  bool changed = false;
  for (const char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '-' || c == '_';
    out += keep ? c : '_';
    changed |= !keep;
  }
  if (!out.empty() && out.front() == '.') out.front() = '_', changed = true;  // not hidden, never "." or ".."
  if (out.size() > 80) out.resize(80), changed = true;
  if (out.empty()) out.push_back('_'), changed = true;
  if (changed) {  // piece by piece: "-" + string trips GCC 12's false -Wrestrict (bug 105651)
    out += '-';
    out += core::sha256_hex(name).substr(0, 8);
  }
  return out;
}

FolderLock::FolderLock(const fs::path& dir, bool claimed) : dir_(dir) {
  std::error_code ec;
  made_ = claimed || !fs::exists(dir, ec);
  fs::create_directories(dir, ec);
  if (ec) throw input_error(dir.string() + ": cannot create the output folder: " + ec.message());
  fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) throw input_error(dir.string() + ": cannot open the output folder: " + reason(errno));
  const auto refuse = [&](const std::string& what) {
    ::close(fd_);
    fd_ = -1;
    throw input_error(dir.string() + ": " + what);
  };
  if (::access(dir.c_str(), W_OK) != 0) refuse("cannot write in the output folder: " + reason(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
    refuse(errno == EWOULDBLOCK
               ? "another gacompare is writing this folder; wait for it to finish or give another --out"
               : "cannot lock the output folder: " + reason(errno));
  // access(2) answers from the permissions alone (root passes it under /proc
  // and /sys): a file made there, and removed, says whether files can be.
  int probe = ::openat(fd_, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
  if (probe < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {
    const fs::path named = temporary_for(dir / "probe");
    probe = ::open(named.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (probe >= 0) ::unlink(named.c_str());
  }
  if (probe < 0) refuse("cannot write in the output folder: " + reason(errno));
  ::close(probe);
  remove_temporaries(dir, 2);
}

FolderLock::FolderLock(FolderLock&& other) noexcept : fd_(other.fd_), dir_(std::move(other.dir_)), made_(other.made_) {
  other.fd_ = -1;
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  if (made_) ::rmdir(dir_.c_str());  // only when empty: rmdir never removes a file
  ::close(fd_);                       // releases the lock
}

namespace {

// What gacompare writes in an output folder: a run's reports (one scene's, or
// a summary and a folder per scene), an accuracy search's, a sweep's.
bool written_by_us(const fs::path& p) {
  static const std::set<std::string> names = {"results.json", "report.md",    "report.html", "stages.csv",
                                              "trajectories.csv", "replay.html", "summary.json", "accuracy.json",
                                              "accuracy.md", "sweep.json",   "sweep.md",    "sweep.csv",
                                              "sweep.html"};
  const std::string name = p.filename().string();
  return names.count(name) || name.ends_with("_work_precision.svg") || is_temporary(p);
}

// The first entry of `dir` (or of a folder in it: a scene's reports, a sweep's
// cells) that gacompare did not write there; empty when there is none.
fs::path foreign_entry(const fs::path& dir, int depth = 1) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const auto status = it->symlink_status(ec);
    if (fs::is_regular_file(status) && (written_by_us(it->path()) || (depth == 0 && it->path().extension() == ".json")))
      continue;
    if (fs::is_directory(status) && depth > 0) {
      if (auto f = foreign_entry(it->path(), depth - 1); !f.empty()) return f;
      continue;
    }
    return it->path();
  }
  return ec ? dir : fs::path();
}

// The folder a --out names, absolute and without a trailing "/." (a link to a
// folder: the folder), so that its parent and its name are known.
fs::path output_folder(const fs::path& out) {
  std::error_code ec, link;
  fs::path p = fs::absolute(out, ec).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();
  if (fs::is_symlink(fs::symlink_status(p, link)))
    if (const fs::path real = fs::canonical(p, link); !link) p = real;
  if (ec || p == p.root_path()) throw input_error(out.string() + ": cannot be the output folder (a run replaces it whole)");
  return p;
}

}  // namespace

StagedFolder::StagedFolder(const fs::path& out, bool claimed) : out_(output_folder(out)), lock_(out_, claimed) {
  if (const fs::path f = foreign_entry(out_); !f.empty())
    throw input_error(out_.string() + ": holds " + f.string() +
                      ", which gacompare did not write there; a run replaces the whole folder: give an empty or new --out");
  // The sibling a killed run left: nobody else writes this folder (its lock is held).
  std::string prefix = ".";  // piece by piece: "." + string trips GCC 12's false -Wrestrict (bug 105651)
  prefix += out_.filename().string();
  prefix += ".staging-";
  std::error_code ec;
  for (fs::directory_iterator it(out_.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size() &&
        name.find_first_not_of("0123456789", prefix.size()) == std::string::npos)
      fs::remove_all(it->path(), ec);
  }
  staging_ = out_.parent_path() / (prefix + std::to_string(::getpid()));
  fs::remove_all(staging_, ec);
  if (::mkdir(staging_.c_str(), 0777) != 0)
    throw input_error(out_.string() + ": cannot create " + staging_.filename().string() +
                      " beside it, where the run's files are written before they replace the folder whole: " +
                      reason(errno));
}

StagedFolder::~StagedFolder() {
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
}

void StagedFolder::commit() {
  std::error_code ec;
  // One rename swaps the two: the previous folder lands at the staging name.
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, out_.c_str(), RENAME_EXCHANGE) == 0) {
    committed_ = true;
    fs::remove_all(staging_, ec);
    return;
  }
  if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP)
    throw run_error(out_.string() + ": cannot put the finished folder in place: " + reason(errno));
  // A file system without the exchange: two renames, the previous folder kept
  // beside it (.NAME.staging-PID-old) until the new one is in place.
  const fs::path old = staging_.string() + "-old";
  fs::remove_all(old, ec);
  if (::rename(out_.c_str(), old.c_str()) != 0 || ::rename(staging_.c_str(), out_.c_str()) != 0)
    throw run_error(out_.string() + ": cannot put the finished folder in place: " + reason(errno));
  committed_ = true;
  fs::remove_all(old, ec);
}

fs::path claim_default_folder(const std::string& what, const std::string& date) {
  const fs::path reports = "reports";
  std::error_code ec;
  fs::create_directories(reports, ec);
  if (ec) throw input_error(reports.string() + ": cannot create the reports folder: " + ec.message());
  std::string leaf = file_name_for(what);
  leaf += '-';
  leaf += date;
  const std::string base = (reports / leaf).string();
  for (int n = 1; n <= 1000; ++n) {
    const std::string candidate = n == 1 ? base : base + "-" + std::to_string(n);
    if (::mkdir(candidate.c_str(), 0777) == 0) return candidate;
    if (errno != EEXIST) throw input_error(candidate + ": cannot create the output folder: " + reason(errno));
  }
  throw input_error(base + ": a thousand folders of that name already; give --out");
}

}  // namespace gacompare::compare
