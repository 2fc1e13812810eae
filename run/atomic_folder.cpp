#include "run/atomic_folder.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "bim/input_error.hpp"

namespace isg::run {

namespace fs = std::filesystem;

void writeFile(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
  if (!out) throw bim::InputError(path.string(), "", "cannot write file");
}

void writeFolderAtomically(const std::string& dir, bool overwrite,
                           const std::function<void(const fs::path&)>& fill) {
  const fs::path target(dir);
  if (fs::exists(target) && !overwrite) {
    throw bim::InputError(dir, "", "already exists (use --force to replace it)");
  }
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent)) {
    throw bim::InputError(dir, "",
                          "cannot write: directory " + parent.string() + " does not exist");
  }
  const fs::path temporary =
      parent / ("." + target.filename().string() + ".partial" + std::to_string(::getpid()));
  fs::remove_all(temporary);
  fs::create_directories(temporary);
  try {
    fill(temporary);
    if (fs::exists(target)) fs::remove_all(target);
    fs::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temporary, ignored);
    throw;
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) {
    throw bim::InputError(path, "", "cannot write: directory " + dir.string() + " does not exist");
  }
  const fs::path temporary =
      dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw bim::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
    }
    out << content;
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw bim::InputError(path, "", "cannot write: write failed");
    }
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw bim::InputError(path, "", "cannot write: " + error.message());
  }
}

}  // namespace isg::run
