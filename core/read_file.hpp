#pragma once
// The one way gacompare reads an input file (scenes, meshes, results,
// baselines, sweep cells and manifests, accuracy caches): a regular file only,
// never a FIFO, a device, a socket or a folder (each refused at once, before a
// byte is read, so /dev/zero cannot fill memory and a FIFO cannot block), at
// most max_input_bytes() long, and never through a symbolic link unless the
// caller says the path is the user's own (a path typed on the command line).
// Every refusal is input_error: one line naming the file and what was wrong.
#include <cstdint>
#include <filesystem>
#include <string>

namespace gacompare::core {

// The largest input file read, by default: a results.json of a million
// samples of a few bodies is about 200 MB, a scene or a cell a few kB.
inline constexpr std::uint64_t kDefaultMaxInputBytes = 256'000'000;  // 256 MB (MB = 1e6 bytes, as --max-memory)
// The limit in force (the command line's --max-input-mb sets it).
std::uint64_t max_input_bytes();
void set_max_input_bytes(std::uint64_t bytes);

// follow: a symbolic link at the end of the path is followed (the user named
// it). refuse: the path was found in a folder or written in another file, and
// a link there is refused (a link in a folder handed over could point anywhere:
// /etc/shadow, /dev/zero).
enum class Links { follow, refuse };

// The whole file. `what` names it in messages ("scene file", "baseline").
std::string read_file(const std::filesystem::path& file, const std::string& what, Links links = Links::refuse);

// A message on one line of valid UTF-8: control characters become spaces and
// bytes that are not well-formed UTF-8 become '?'.
std::string one_line(const std::string& s);

}  // namespace gacompare::core
