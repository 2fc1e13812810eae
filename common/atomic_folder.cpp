#include "common/atomic_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "common/input_error.hpp"

namespace isg::common {

namespace fs = std::filesystem;

namespace {

// Opens `path` for writing, writes into it with `write` (false: a write failed, errno says why),
// closes it; a failure is an InputError naming the path. C stdio rather than a stream: errno then
// says why a write failed (a full disk, a quota).
template <typename Write>
void writeWith(const fs::path& path, const Write& write) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    throw common::InputError(path.string(), "",
                             std::string("cannot write: ") + std::strerror(errno));
  }
  bool written = false;
  try {
    written = write(file);
  } catch (...) {
    std::fclose(file);
    throw;
  }
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    throw common::InputError(
        path.string(), "",
        std::string("cannot write: ") + std::strerror(!written ? write_errno : errno));
  }
}

bool writeAll(std::FILE* file, const std::string& text) {
  return std::fwrite(text.data(), 1, text.size(), file) == text.size();
}

}  // namespace

void writeFile(const fs::path& path, const std::string& content) {
  writeWith(path, [&](std::FILE* file) { return writeAll(file, content); });
}

void writeFileInParts(const fs::path& path, const std::function<std::string()>& next_part) {
  writeWith(path, [&](std::FILE* file) {
    for (std::string part = next_part(); !part.empty(); part = next_part()) {
      if (!writeAll(file, part)) return false;
    }
    return true;
  });
}

namespace {

// ".NAME.partial" + pid: the temporary folder a run writes NAME in.
std::string partialPrefix(const fs::path& target) {
  return "." + target.filename().string() + ".partial";
}

// Removes the temporary folders of earlier runs that were killed (SIGKILL, a power cut) while
// writing `target`: their process is gone. A folder of a process still running is left alone.
void removeStalePartials(const fs::path& parent, const fs::path& target) {
  const std::string prefix = partialPrefix(target);
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(parent, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
        digits.size() > 9) {
      continue;
    }
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid == ::getpid() || (::kill(pid, 0) != 0 && errno == ESRCH)) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }
}

// Exchanges the two paths in one step (Linux renameat2 RENAME_EXCHANGE), so that `target` always
// holds a whole folder, the old one or the new one. Replacing it by removing it first left a
// half-removed folder at the output path when the process was killed meanwhile (the kill test
// caught it). False where the file system cannot exchange; the caller then removes and renames.
bool swapFolders(const fs::path& a, const fs::path& b) {
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0;
}

}  // namespace

fs::path requireParentFolder(const std::string& path) {
  const fs::path target(path);
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // The nearest part of the parent that exists must be a folder this process may write in: what
  // is missing below it is made when the output is written (MadeFolders), after every check.
  fs::path existing = parent;
  std::error_code error;
  while (!fs::exists(fs::symlink_status(existing, error)) && existing.has_relative_path() &&
         existing.has_parent_path() && existing.parent_path() != existing) {
    existing = existing.parent_path();
  }
  if (!fs::exists(fs::symlink_status(existing, error))) existing = ".";
  if (!fs::is_directory(existing, error)) {
    throw common::InputError(path, "",
                             "cannot write: " + existing.string() + " is not a directory");
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    const std::string reason = std::strerror(errno);
    throw common::InputError(path, "",
                             existing == parent
                                 ? "cannot write: " + reason
                                 : "cannot write in " + existing.string() + ": " + reason);
  }
  return parent;
}

MadeFolders::MadeFolders(const fs::path& folder) {
  std::vector<fs::path> missing;
  std::error_code error;
  for (fs::path p = folder; !p.empty() && !fs::exists(fs::symlink_status(p, error));
       p = p.parent_path()) {
    missing.push_back(p);
    if (!p.has_parent_path() || p.parent_path() == p) break;
  }
  for (auto p = missing.rbegin(); p != missing.rend(); ++p) {
    if (!fs::create_directory(*p, error) && error) {
      const std::string why = error.message();
      removeMade();
      throw common::InputError(p->string(), "", "cannot make the folder: " + why);
    }
    made_.push_back(*p);
  }
}

MadeFolders::~MadeFolders() { removeMade(); }

void MadeFolders::removeMade() {
  // Deepest first; a folder something else has written into since is not empty and stays.
  std::error_code ignored;
  while (!made_.empty()) {
    fs::remove(made_.back(), ignored);
    made_.pop_back();
  }
}

namespace {

// Checks `path` against the output rule and names its temporary twin beside it (stale twins of
// killed processes removed).
fs::path temporaryPathFor(const std::string& path, const OutputRule& rule) {
  const fs::path target = checkOutputPath(path, rule);  // the parent checked there too
  const fs::path parent = target.parent_path();
  removeStalePartials(parent, target);
  return parent / (partialPrefix(target) + std::to_string(::getpid()));
}

fs::path createTemporaryFolder(const std::string& dir, const fs::path& temporary) {
  std::error_code error;
  fs::create_directory(temporary, error);
  if (error) throw common::InputError(dir, "", "cannot write: " + error.message());
  return temporary;
}

}  // namespace

void checkCanCreateFolder(const std::string& dir, OutputKind kind, bool overwrite,
                          const std::vector<std::string>& inputs) {
  const fs::path temporary = temporaryPathFor(dir, {kind, inputs, overwrite});
  // A probe: the folder (and any missing folder above it) made and removed again, so that a path
  // that cannot be written fails now rather than after hours of work.
  const MadeFolders parents(temporary.parent_path());
  std::error_code ignored;
  fs::remove(createTemporaryFolder(dir, temporary), ignored);
}

void writeFolderAtomically(const std::string& dir, OutputKind kind, bool overwrite,
                           const std::function<void(const fs::path&)>& fill) {
  const OutputRule rule{kind, {}, overwrite};
  const fs::path temporary_path = temporaryPathFor(dir, rule);
  MadeFolders parents(temporary_path.parent_path());
  const fs::path temporary = createTemporaryFolder(dir, temporary_path);
  const fs::path target = checkOutputPath(dir, rule);
  std::error_code error;
  try {
    try {
      fill(temporary);
      writeOutputMarker(temporary, kind);
    } catch (const common::InputError& e) {
      // A file inside the temporary folder is named as it would have been in the real one.
      const std::string file = e.file();
      const std::string inside = temporary.string() + "/";
      if (file.rfind(inside, 0) != 0) throw;
      throw common::InputError((fs::path(dir) / file.substr(inside.size())).string(), e.pointer(),
                               e.reason());
    }
    // Checked again at the last moment: what the path holds now is what gets replaced.
    checkOutputPath(dir, rule);
    if (fs::exists(target) && swapFolders(temporary, target)) {
      // The old folder now has the temporary name: if this process dies while removing it, the
      // next run to the same path removes it (removeStalePartials).
      fs::remove_all(temporary, error);
      parents.keep();
      return;
    }
    if (fs::exists(target)) {
      // No exchange on this file system: the old folder is moved aside, never removed before the
      // new one is in place.
      const fs::path aside = temporary.string() + ".replaced";
      fs::rename(target, aside, error);
      if (error) throw common::InputError(dir, "", "cannot replace: " + error.message());
      fs::rename(temporary, target, error);
      if (error) {
        std::error_code ignored;
        fs::rename(aside, target, ignored);
        throw common::InputError(dir, "", "cannot write: " + error.message());
      }
      fs::remove_all(aside, error);
      parents.keep();
      return;
    }
    fs::rename(temporary, target, error);
    if (error) throw common::InputError(dir, "", "cannot write: " + error.message());
    parents.keep();
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temporary, ignored);
    throw;
  }
}

AtomicFile::AtomicFile(const std::string& path, OutputKind kind, bool overwrite)
    : path_(checkOutputPath(path, {kind, {}, overwrite})),
      temporary_(temporaryPathFor(path, {kind, {}, overwrite})),
      parents_(temporary_.parent_path()) {}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  std::error_code error;
  fs::rename(temporary_, path_, error);  // replaces an existing file in one step
  if (error) throw common::InputError(path_.string(), "", "cannot write: " + error.message());
  committed_ = true;
  parents_.keep();
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  const fs::path target(path);
  const fs::path dir = requireParentFolder(path);
  MadeFolders parents(dir);
  const fs::path temporary =
      dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw common::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
    }
    errno = 0;
    out << content;
    out.flush();
    if (!out) {
      // The stream keeps no reason; the failed write(2) left it in errno (a full disk, a quota).
      const std::string reason = errno != 0 ? std::strerror(errno) : "write failed";
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw common::InputError(path, "", "cannot write: " + reason);
    }
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw common::InputError(path, "", "cannot write: " + error.message());
  }
  parents.keep();
}

}  // namespace isg::common
