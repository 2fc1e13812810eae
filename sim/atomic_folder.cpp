#include "sim/atomic_folder.hpp"

#include <unistd.h>

#include <fstream>

#include "bim/input_error.hpp"

namespace isg::sim {

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

}  // namespace isg::sim
