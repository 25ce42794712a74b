#pragma once
// The files and folders gacompare writes, and its unique default folders: a run killed at any moment, or two runs given the
// same --out, never leave half a file or one run's results beside another's
// report.
#include <filesystem>
#include <string>

namespace gacompare::compare {

// Writes `text` to `path` so that `path` is at every moment either what it was
// or all of `text`: the text goes to an anonymous file in the same folder
// (O_TMPFILE), which gets a name only once complete, and that name is renamed
// over `path`. Where the file system has no anonymous files, a temporary named
// .NAME.PID-N.tmp is used instead and removed when anything fails. Throws
// run_error naming the file and the system's reason (a full disk says "No space
// left on device") and leaves no temporary behind.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

// A name from a scene file as one file-name component: letters, digits, '.',
// '-' and '_' kept, anything else '_', at most 80 bytes; a name that had to be
// changed gets '-' and 8 hex digits of its SHA-256 appended, so two names never
// share a folder. Ordinary names come back unchanged; the real name stays in
// the results.
std::string file_name_for(const std::string& name);

// An exclusive lock on an output folder for as long as this object lives,
// taken before any work: the folder is created (with its parents) and locked
// with flock(2), which the kernel releases when the process ends, kill -9
// included, so a lock is never left behind. Temporaries a killed run left in
// the folder (and its subfolders) are removed once the lock is held. Throws
// input_error (exit 2) naming the folder when it cannot be created or written
// (a file is made and removed there to know: access(2) says yes to root under
// /proc), or when another gacompare holds it. A folder it made (or that was `claimed`
// for it, claim_default_folder) and that is still empty when the lock goes is
// removed: a run refused before writing anything leaves no trace.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& dir, bool claimed = false);
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&&) = delete;
  FolderLock(const FolderLock&) = delete;
  ~FolderLock();

 private:
  int fd_ = -1;
  std::filesystem::path dir_;
  bool made_ = false;
};

// An output folder written whole or not at all (run, compare, merge): its
// files go into a sibling folder, .NAME.staging-PID, made before any work (a
// parent that cannot be written is refused then, exit 2, not after the runs),
// and commit() puts that folder in NAME's place in one rename (Linux's
// RENAME_EXCHANGE: NAME is at every moment the previous complete folder or
// the new one), then removes the previous one. A run that fails, or is
// killed, leaves NAME as it was; the sibling a killed run left is removed by
// the next run given NAME (under NAME's lock, FolderLock). Since the whole
// folder is replaced, NAME must be new, empty, or hold only what gacompare
// writes there (its reports, a sweep's cells); anything else is refused, exit
// 2, before any work. NAME may be a link to a folder: that folder is replaced.
// Throws input_error naming the folder.
class StagedFolder {
 public:
  explicit StagedFolder(const std::filesystem::path& out, bool claimed = false);
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;
  ~StagedFolder();
  const std::filesystem::path& path() const { return staging_; }  // where the files go
  // Puts the folder in place. Throws run_error naming the folder when it cannot.
  void commit();

 private:
  std::filesystem::path out_, staging_;
  FolderLock lock_;
  bool committed_ = false;
};

// The default output folder, reports/<file_name_for(what)>-<UTC date>, made
// unique: two runs started in the same second get -2, -3, ... (the folder is
// claimed with mkdir, which only one process can win).
std::filesystem::path claim_default_folder(const std::string& what, const std::string& date);

}  // namespace gacompare::compare
