#include "core/read_file.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gacompare::core {

namespace {

std::atomic<std::uint64_t> max_bytes{kDefaultMaxInputBytes};

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link (not followed: a link found in a folder or named in a file could lead anywhere)";
  return "something that is not a regular file";
}

std::string megabytes(std::uint64_t bytes) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g MB", static_cast<double>(bytes) / 1e6);
  return buffer;
}

}  // namespace

std::uint64_t max_input_bytes() { return max_bytes.load(); }
void set_max_input_bytes(std::uint64_t bytes) { max_bytes.store(bytes); }

std::string read_file(const std::filesystem::path& file, const std::string& what, Links links) {
  const std::string where = file.string();
  const auto refuse = [&](const std::string& why) { throw input_error(one_line(where + ": " + why)); };
  // `bytes`: its size (stat), or 0 when the read went past the limit (its size read less).
  const auto too_large = [&](std::uint64_t bytes) {
    refuse("the " + what + " is " + (bytes ? megabytes(bytes) : "more than " + megabytes(max_input_bytes())) +
           ", above the limit of " + megabytes(max_input_bytes()) + " (--max-input-mb raises it)");
  };
  // Its kind first, from the path alone: opening a device or a FIFO can block
  // or act (a tape rewinds), so neither is opened.
  struct stat st {};
  const int found = links == Links::follow ? ::stat(where.c_str(), &st) : ::lstat(where.c_str(), &st);
  if (found != 0) refuse("cannot open the " + what + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) refuse("expected a " + what + ", got " + kind_of(st.st_mode));
  // O_NOFOLLOW and O_NONBLOCK: a path swapped for a link or a FIFO since is refused, never waited on.
  const int fd = ::open(where.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK | (links == Links::refuse ? O_NOFOLLOW : 0));
  if (fd < 0) refuse("cannot open the " + what + ": " + std::strerror(errno));
  const auto close_and_refuse = [&](const std::string& why) {
    ::close(fd);
    refuse(why);
  };
  if (::fstat(fd, &st) != 0) close_and_refuse("cannot read the " + what + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) close_and_refuse("expected a " + what + ", got " + kind_of(st.st_mode));
  const std::uint64_t limit = max_input_bytes();
  if (static_cast<std::uint64_t>(st.st_size) > limit) {
    ::close(fd);
    too_large(static_cast<std::uint64_t>(st.st_size));
  }
  // Read to the limit and one byte past it: a file that grows meanwhile, or a
  // kernel file whose size reads 0, is still bounded.
  std::string text;
  text.resize(static_cast<std::size_t>(st.st_size) + 1);
  std::size_t done = 0;
  for (;;) {
    if (done == text.size()) {
      if (done > limit) break;
      text.resize(std::min<std::uint64_t>(limit + 1, std::max<std::uint64_t>(2 * text.size(), 65536)));
    }
    const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) close_and_refuse("cannot read the " + what + ": " + std::strerror(errno));
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (done > limit) too_large(0);
  text.resize(done);
  return text;
}

std::string one_line(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    const std::size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 0;
    bool ok = n > 0 && i + n <= s.size();
    for (std::size_t k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(s[i + k]) >> 6) == 0x2;
    if (!ok) {
      out += '?';
      ++i;
    } else if (b < 0x20 || b == 0x7f) {
      out += ' ';
      ++i;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  return out;
}

}  // namespace gacompare::core
