#pragma once

// The one-way module rule of docs/architecture.md, checked from the sources: every module's
// `#include "…"` and `#include <…>` lines and the libraries its CMakeLists.txt links. A module's
// tests/ and bench/ follow the module's own rule.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace isg::architecture {

namespace fs = std::filesystem;

// The allowed direct dependencies between modules (the arrows of docs/architecture.md).
inline const std::map<std::string, std::set<std::string>>& allowedModules() {
  static const std::map<std::string, std::set<std::string>> allowed{
      {"common", {}},
      {"bim", {"common"}},
      {"bim/optimizer", {"common", "bim"}},
      {"worlds", {"common", "bim"}},
      {"ifc", {"common", "bim"}},
      {"raster", {"common", "bim"}},
      {"eval", {"common"}},
      {"sensors", {"common"}},
      {"formats", {"common", "sensors"}},
      {"recordings", {"common", "sensors", "formats"}},
      {"slam", {"common", "bim", "sensors"}},
      {"slam/sgraph", {"common", "bim", "bim/optimizer", "sensors", "slam"}},
      {"slam/isgraph", {"common", "bim", "bim/optimizer", "sensors", "slam", "slam/sgraph"}},
      {"slam/baselines", {"common", "bim", "sensors", "slam"}},
      {"slam/deviations", {"common", "bim", "slam"}},
      {"run",
       {"common", "bim", "eval", "sensors", "formats", "slam", "slam/sgraph", "slam/isgraph",
        "slam/baselines", "slam/deviations"}},
      {"run/foxglove", {"common", "bim", "sensors", "formats", "slam", "slam/deviations", "run"}},
      {"run/bcf", {"common", "bim", "slam", "slam/deviations"}},
      {"sim", {"common", "bim", "worlds", "sensors", "formats"}},
      {"sweep", {"common", "bim", "worlds", "eval", "run", "sim"}},
      {"cli",
       {"common",
        "bim",
        "bim/optimizer",
        "worlds",
        "ifc",
        "raster",
        "eval",
        "sensors",
        "formats",
        "recordings",
        "slam",
        "slam/sgraph",
        "slam/isgraph",
        "slam/baselines",
        "slam/deviations",
        "run",
        "run/foxglove",
        "run/bcf",
        "sim",
        "sweep"}},
  };
  return allowed;
}

// Where a module may reach into another only for some headers.
inline bool headerAllowed(const std::string& from, const std::string& header) {
  // slam's PCL header is slam's own: no user of slam compiles PCL.
  if (header == "slam/sgraph/pcl_planes.hpp") return from == "slam/sgraph";
  return true;
}

// The headers of the codecs and message libraries that only formats/ uses (compression, SQLite,
// Debian's ROS 1 message headers): the localizers must not carry them.
inline bool isCodecHeader(const std::string& header) {
  static const std::set<std::string> codecs{"lzf.h",  "bzlib.h", "lz4.h",     "lz4frame.h",
                                            "zstd.h", "zlib.h",  "sqlite3.h", "jpeglib.h"};
  if (codecs.count(header)) return true;
  for (const char* ros :
       {"ros/", "sensor_msgs/", "nav_msgs/", "geometry_msgs/", "tf2_msgs/", "std_msgs/"}) {
    if (header.rfind(ros, 0) == 0) return true;
  }
  return false;
}

struct Violation {
  std::string file;  // relative to the root
  int line = 0;
  std::string what;
  std::string str() const { return file + ":" + std::to_string(line) + ": " + what; }
};

inline std::string join(const std::set<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// The module a path is in, the longest one that holds it: "slam/sgraph/sgraph.cpp" →
// "slam/sgraph", "slam/tests/x.cpp" → "slam", "run/driver.hpp" → "run"; "" outside the modules.
inline std::string moduleOf(const std::string& path) {
  std::string best;
  for (const auto& [module, _] : allowedModules()) {
    if (path.size() > module.size() && path.compare(0, module.size(), module) == 0 &&
        path[module.size()] == '/' && module.size() > best.size())
      best = module;
  }
  return best;
}
inline std::string moduleOf(const fs::path& relative) { return moduleOf(relative.string()); }

// The module whose library is isg_<name>: a module's library is named after its last folder
// ("slam/sgraph" → isg_sgraph); "" for other names.
inline std::string moduleOfLibrary(const std::string& name) {
  for (const auto& [module, _] : allowedModules()) {
    const auto slash = module.rfind('/');
    if ((slash == std::string::npos ? module : module.substr(slash + 1)) == name) return module;
  }
  return "";
}

inline void checkIncludes(const fs::path& root, const fs::path& relative,
                          std::vector<Violation>& out) {
  const std::string module = moduleOf(relative);
  const bool header = relative.extension() == ".hpp" || relative.extension() == ".h";
  const bool in_tests = relative.string().find("/tests/") != std::string::npos ||
                        relative.string().find("/bench/") != std::string::npos;
  std::ifstream in(root / relative);
  const std::regex quoted(R"(^\s*#\s*include\s*"([^"]+)\")");
  const std::regex angled(R"(^\s*#\s*include\s*<([^>]+)>)");
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::smatch m;
    if (std::regex_search(line, m, quoted)) {
      const std::string target = m[1];
      if (target.find('/') == std::string::npos) continue;  // a file beside it (generated, tests')
      const std::string to = moduleOf(target);
      if (to.empty() || to == module) continue;
      if (!allowedModules().at(module).count(to)) {
        out.push_back({relative.string(), number,
                       module + " may not include \"" + target +
                           "\" (allowed: " + join(allowedModules().at(module)) + ")"});
      } else if (!headerAllowed(module, target)) {
        out.push_back({relative.string(), number,
                       module + " may not include \"" + target + "\" (docs/architecture.md)"});
      }
    } else if (std::regex_search(line, m, angled)) {
      const std::string target = m[1];
      if (target.rfind("mujoco/", 0) == 0 && module != "sim") {
        out.push_back({relative.string(), number,
                       module + " may not include MuJoCo (<" + target + ">): only sim runs it"});
      }
      if (isCodecHeader(target) && module != "formats") {
        out.push_back({relative.string(), number,
                       module + " may not include <" + target +
                           ">: file formats and their codecs stay inside formats"});
      }
      if (target.rfind("pcl/", 0) == 0) {
        const bool private_pcl = relative == fs::path("slam/sgraph/pcl_planes.hpp") ||
                                 (!header && (module == "slam" || module.rfind("slam/", 0) == 0)) ||
                                 (in_tests && module == "sim");
        if (!private_pcl) {
          out.push_back({relative.string(), number,
                         module + " may not include PCL (<" + target +
                             ">) here: PCL stays inside slam's sources"});
        }
      }
    }
  }
}

// The calls of a CMakeLists.txt that link libraries: (line of each token, token).
inline void checkLinks(const fs::path& root, const fs::path& relative,
                       std::vector<Violation>& out) {
  const std::string module = moduleOf(relative);
  std::ifstream in(root / relative);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::regex call(R"((target_link_libraries|isg_add_tests|isg_add_bench)\s*\()");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), call); it != std::sregex_iterator();
       ++it) {
    const std::size_t open = it->position() + it->length();
    const std::size_t close = text.find(')', open);
    const int line = 1 + int(std::count(text.begin(), text.begin() + it->position(), '\n'));
    std::istringstream arguments(text.substr(open, close - open));
    std::vector<std::string> tokens;
    for (std::string t; arguments >> t;) tokens.push_back(t);
    if (tokens.empty()) continue;
    // The target's module: isg_<m>, <m>_tests, <m>_bench, or the helper's first argument.
    std::string target = tokens[0];
    for (const char* suffix : {"_tests", "_bench"}) {
      const std::string s = suffix;
      if (target.size() > s.size() && target.compare(target.size() - s.size(), s.size(), s) == 0)
        target = target.substr(0, target.size() - s.size());
    }
    if (target.rfind("isg_", 0) == 0) target = target.substr(4);
    if (moduleOfLibrary(target) != module)
      continue;  // another target (the isg executable, a test helper)
    for (std::size_t i = 1; i < tokens.size(); ++i) {
      const std::string& library = tokens[i];
      if (library.rfind("mujoco", 0) == 0 && module != "sim") {
        out.push_back({relative.string(), line, module + " may not link " + library});
      }
      if (library.rfind("isg_", 0) != 0) continue;
      const std::string to = moduleOfLibrary(library.substr(4));
      if (to.empty() || to == module) continue;
      if (!allowedModules().at(module).count(to)) {
        out.push_back({relative.string(), line,
                       module + " may not link " + library +
                           " (allowed: " + join(allowedModules().at(module)) + ")"});
      }
    }
  }
}

// Every violation under `root`, in file order.
inline std::vector<Violation> check(const fs::path& root) {
  std::set<fs::path> files;  // a set: a nested module's files are also under its parent's folder
  for (const auto& [module, _] : allowedModules()) {
    if (!fs::is_directory(root / module)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / module)) {
      if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), root));
    }
  }
  std::vector<Violation> out;
  for (const auto& file : files) {
    const auto ext = file.extension();
    if (ext == ".cpp" || ext == ".hpp" || ext == ".h" || ext == ".in")
      checkIncludes(root, file, out);
    if (file.filename() == "CMakeLists.txt") checkLinks(root, file, out);
  }
  return out;
}

}  // namespace isg::architecture
