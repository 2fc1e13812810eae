#pragma once

// The size rule of docs/architecture.md ("Function length"), checked from the sources: no function
// of a module's sources (outside tests/, bench/ and fuzz/) is over kMaxFunctionLines lines, as
// universal-ctags measures them (a function's first line to its closing brace), but those on the
// allow-list below, each with the reason it stays whole, and none of those over
// kHardFunctionLines.

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "architecture_rules.hpp"

namespace isg::architecture {

inline constexpr int kMaxFunctionLines = 100;
inline constexpr int kHardFunctionLines = 150;

// A function allowed over kMaxFunctionLines: its file (from the root), its name as ctags gives it
// (a constructor's is its class's), and why it stays whole.
struct LongFunction {
  std::string file, name, why;
};

inline const std::vector<LongFunction>& allowedLongFunctions() {
  // None now: the two command option tables it held (ImportCommand, GenerateCommand) are split
  // by option group. An entry needs a reason of its own.
  static const std::vector<LongFunction> allowed{};
  return allowed;
}

struct FunctionExtent {
  std::string file, name;
  int line = 0, lines = 0;
};

// The sources the rule covers: .cpp and .hpp files of the modules, outside tests/, bench/, fuzz/.
inline std::vector<std::string> sourcesUnderRule(const fs::path& root) {
  std::set<std::string> files;
  for (const auto& [module, _] : allowedModules()) {
    if (!fs::is_directory(root / module)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / module)) {
      const fs::path relative = fs::relative(entry.path(), root);
      const std::string text = relative.string();
      if (!entry.is_regular_file()) continue;
      if (relative.extension() != ".cpp" && relative.extension() != ".hpp") continue;
      if (text.find("/tests/") != std::string::npos || text.find("/bench/") != std::string::npos ||
          text.find("/fuzz/") != std::string::npos)
        continue;
      files.insert(text);
    }
  }
  return {files.begin(), files.end()};
}

// Every function's extent in `files` (relative to root), by universal-ctags run from `root`
// (`ctags` names the program). Throws when ctags cannot be run.
inline std::vector<FunctionExtent> functionExtents(const fs::path& root,
                                                   const std::vector<std::string>& files,
                                                   const std::string& ctags) {
  const fs::path list = fs::temp_directory_path() / ("isg_ctags_" + std::to_string(::getpid()));
  {
    std::ofstream out(list);
    for (const auto& f : files) out << f << "\n";
  }
  const std::string command = "cd '" + root.string() + "' && '" + ctags + "' -L '" + list.string() +
                              "' --c++-kinds=f --fields=+ne -u -o - 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot run " + ctags);
  std::string output;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe.get())) output.append(buffer, n);
  const int status = pclose(pipe.release());
  fs::remove(list);
  if (status != 0)
    throw std::runtime_error(ctags + " failed (status " + std::to_string(status) + ")");
  std::vector<FunctionExtent> out;
  std::istringstream lines(output);
  for (std::string row; std::getline(lines, row);) {
    std::vector<std::string> fields;
    std::size_t from = 0;
    for (std::size_t tab; (tab = row.find('\t', from)) != std::string::npos; from = tab + 1)
      fields.push_back(row.substr(from, tab - from));
    fields.push_back(row.substr(from));
    if (fields.size() < 4) continue;
    FunctionExtent extent{fields[1], fields[0], 0, 0};
    int end = 0;
    for (std::size_t i = 3; i < fields.size(); ++i) {
      if (fields[i].rfind("line:", 0) == 0) extent.line = std::stoi(fields[i].substr(5));
      if (fields[i].rfind("end:", 0) == 0) end = std::stoi(fields[i].substr(4));
    }
    if (extent.line == 0 || end == 0) continue;
    extent.lines = end - extent.line + 1;
    out.push_back(extent);
  }
  return out;
}

// Every breach of the size rule, one line each: a function over the limit and not allowed, an
// allowed one over the hard limit, an allowed one that is no longer long (its entry goes).
inline std::vector<std::string> checkFunctionLengths(const std::vector<FunctionExtent>& extents,
                                                     const std::vector<LongFunction>& allowed) {
  std::vector<std::string> out;
  std::map<std::pair<std::string, std::string>, const LongFunction*> allowed_by_key;
  for (const auto& a : allowed) allowed_by_key[{a.file, a.name}] = &a;
  std::set<std::pair<std::string, std::string>> still_long;
  for (const auto& f : extents) {
    if (f.lines <= kMaxFunctionLines) continue;
    const std::string where = f.file + ":" + std::to_string(f.line) + ": " + f.name + " is " +
                              std::to_string(f.lines) + " lines";
    const auto found = allowed_by_key.find({f.file, f.name});
    if (found == allowed_by_key.end()) {
      out.push_back(where + ", over " + std::to_string(kMaxFunctionLines) +
                    ": split it into named steps (docs/architecture.md, \"Function length\")");
    } else {
      still_long.insert({f.file, f.name});
      if (f.lines > kHardFunctionLines) {
        out.push_back(where + ", over " + std::to_string(kHardFunctionLines) +
                      " even on the allow-list: split it");
      }
    }
  }
  for (const auto& a : allowed) {
    if (!still_long.count({a.file, a.name})) {
      out.push_back(a.file + ": " + a.name + " is on the allow-list but no longer over " +
                    std::to_string(kMaxFunctionLines) +
                    " lines (or gone): take it off (cli/tests/function_length_rules.hpp)");
    }
  }
  return out;
}

}  // namespace isg::architecture
