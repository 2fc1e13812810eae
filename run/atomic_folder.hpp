#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace isg::run {

// Creates the folder `dir` all at once: `fill` writes into a temporary folder beside it, which is
// renamed into place when `fill` returns (an existing folder is exchanged with it in one step,
// then removed); if it throws, the temporary folder is removed and nothing is left half-written. An
// existing `dir` is an InputError unless `overwrite`, and so is a parent directory that does not
// exist. Used for dataset and run folders.
void writeFolderAtomically(const std::string& dir, bool overwrite,
                           const std::function<void(const std::filesystem::path&)>& fill);

// The checks writeFolderAtomically starts with, for a command to run before hours of work:
// `dir` may be created (it does not exist, or `overwrite`; its parent exists and is writable).
// Probes by creating and removing the temporary folder; earlier runs' stale ones are removed.
void checkCanCreateFolder(const std::string& dir, bool overwrite);

// A file too large to build in memory, made all at once: the caller writes temporary() (beside
// `path`, named like writeFolderAtomically's folders so that a killed process's leftover is
// removed by the next write to the same path), then commit() renames it into place. Destroyed
// uncommitted (an error, an interrupt), it removes the temporary file. An existing `path` is an
// InputError unless `overwrite`, as is a directory at `path` or a missing parent directory.
class AtomicFile {
 public:
  AtomicFile(const std::string& path, bool overwrite);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& path() const { return path_; }
  void commit();

 private:
  std::filesystem::path path_, temporary_;
  bool committed_ = false;
};

// One file of such a folder; a failure is an InputError naming it.
void writeFile(const std::filesystem::path& path, const std::string& content);

// The folder `path` would be written into (its parent, "." for a bare name) exists: an InputError
// naming `path` says the folder does not exist, or is a file, otherwise. Returns that folder.
std::filesystem::path requireParentFolder(const std::string& path);

// Writes `content` to `path` so that a reader never sees a half-written file: to a temporary
// file beside it, then renamed over it. A failure is an InputError naming the path.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace isg::run
