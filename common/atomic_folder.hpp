#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/output_path.hpp"

namespace isg::common {

// The folders an output's path needs that do not exist yet, made when the output is written
// (after every check, never before) and removed again, deepest first and only while empty, unless
// keep() is called once the output is in place: a failed write leaves no empty folders behind.
class MadeFolders {
 public:
  explicit MadeFolders(const std::filesystem::path& folder);
  ~MadeFolders();
  MadeFolders(const MadeFolders&) = delete;
  MadeFolders& operator=(const MadeFolders&) = delete;
  void keep() { made_.clear(); }

 private:
  void removeMade();
  std::vector<std::filesystem::path> made_;
};

// Creates the folder `dir` all at once: `fill` writes into a temporary folder beside it, which is
// renamed into place when `fill` returns (an existing folder is exchanged with it in one step,
// then removed); if it throws, the temporary folder is removed and nothing is left half-written.
// `dir` follows the output rule (checkOutputPath: an existing folder is replaced only with
// `overwrite` and only if it is an output of ours of `kind`); a parent directory that does not
// exist is made (and removed again if the write fails). The folder gets the marker of `kind`
// (kOutputMarkerFile). Used for dataset, run and generated-building folders.
void writeFolderAtomically(const std::string& dir, OutputKind kind, bool overwrite,
                           const std::function<void(const std::filesystem::path&)>& fill);

// The checks writeFolderAtomically starts with, for a command to run before hours of work: the
// output rule with the command's `inputs`, and that the folder may be created: probed by making
// the temporary folder (and the missing folders above it) and removing them again; earlier runs'
// stale temporary folders are removed.
void checkCanCreateFolder(const std::string& dir, OutputKind kind, bool overwrite,
                          const std::vector<std::string>& inputs = {});

// A file too large to build in memory, made all at once: the caller writes temporary() (beside
// `path`, named like writeFolderAtomically's folders so that a killed process's leftover is
// removed by the next write to the same path), then commit() renames it into place. Destroyed
// uncommitted (an error, an interrupt), it removes the temporary file. `path` follows the output
// rule for `kind` (an existing file is replaced only with `overwrite` and only if it is ours);
// missing parent folders are made, and removed again when the file is not committed.
class AtomicFile {
 public:
  AtomicFile(const std::string& path, OutputKind kind, bool overwrite);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& path() const { return path_; }
  void commit();

 private:
  std::filesystem::path path_, temporary_;
  MadeFolders parents_;
  bool committed_ = false;
};

// One file of such a folder; a failure is an InputError naming it.
void writeFile(const std::filesystem::path& path, const std::string& content);
// The same, written part after part as `next_part` gives them (an empty part ends the file): a
// long text need never stand whole in memory.
void writeFileInParts(const std::filesystem::path& path,
                      const std::function<std::string()>& next_part);

// The folder `path` would be written into (its parent, "." for a bare name) exists, or the
// nearest of its ancestors that exists is a folder this process may write in (the writers make
// the missing ones, MadeFolders): an InputError naming `path` says which part is not a folder or
// why it cannot be written in (a read-only file system, no permission). Returns the parent.
std::filesystem::path requireParentFolder(const std::string& path);

// Writes `content` to `path` so that a reader never sees a half-written file: to a temporary
// file beside it, then renamed over it. A failure is an InputError naming the path.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace isg::common
