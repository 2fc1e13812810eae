#include "common/output_path.hpp"

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"

namespace isg::common {

namespace fs = std::filesystem;

namespace {

struct KindInfo {
  OutputKind kind;
  const char* name;  // in the marker file
  const char* description;
  bool folder;
};

constexpr KindInfo kKinds[] = {
    {OutputKind::kRunFolder, "run", "a run folder", true},
    {OutputKind::kDataset, "dataset", "a dataset folder", true},
    {OutputKind::kBuildings, "buildings", "a folder of generated buildings", true},
    {OutputKind::kSweep, "sweep", "a sweep folder", true},
    {OutputKind::kPictures, "pictures", "a folder of pictures", true},
    {OutputKind::kBag, "bag", "a ROS bag", false},
    {OutputKind::kMcap, "mcap", "an MCAP file", false},
    {OutputKind::kSvg, "svg", "an SVG picture", false},
    {OutputKind::kPng, "png", "a PNG picture", false},
    {OutputKind::kMjcf, "mjcf", "an MJCF world", false},
    {OutputKind::kAgraphJson, "agraph", "an A-Graph file", false},
    {OutputKind::kTableMarkdown, "table", "a Markdown table", false},
    {OutputKind::kTableCsv, "table", "a CSV table", false},
    {OutputKind::kTableLatex, "table", "a LaTeX table", false},
    {OutputKind::kImportedPlan, "plan", "an imported plan", false},
    {OutputKind::kSubmission, "submission", "a floor-plan benchmark submission", false},
    {OutputKind::kBcf, "bcf", "a BCF archive", false},
};

const KindInfo& infoOf(OutputKind kind) {
  for (const auto& k : kKinds) {
    if (k.kind == kind) return k;
  }
  return kKinds[0];
}

// The first `bytes` of a file (fewer if it is shorter); empty when it cannot be read.
std::string head(const fs::path& path, std::size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string text(bytes, '\0');
  in.read(text.data(), std::streamsize(bytes));
  text.resize(std::size_t(in.gcount()));
  return text;
}

std::string currentDirectory() {
  std::error_code error;
  const fs::path cwd = fs::current_path(error);
  return error ? std::string() : fs::weakly_canonical(cwd, error).string();
}

// A sweep folder made before the marker existed holds sweep.json; an empty folder is free, and so
// is one that a sweep starting this instant has locked but not yet marked (only its ".lock", or
// the marker being written). The listing is read before the marker: a sweep writes its marker
// before anything else, so when the listing shows any other file, the marker is there by the time
// it is read. Read the other way round, a sweep started beside this one could mark its folder
// and write its worlds between the two reads, and its folder would be taken for a stranger's.
bool mayHoldSweep(const fs::path& folder) {
  std::error_code error;
  bool only_lock_and_marker = true;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (name != ".lock" && name.rfind(kOutputMarkerFile, 0) != 0) {
      only_lock_and_marker = false;
      break;
    }
  }
  if (!error && only_lock_and_marker) return true;
  if (folderOutputKind(folder) == OutputKind::kSweep) return true;
  return fs::is_regular_file(folder / "sweep.json");
}

// isg writes no symbolic links, so one where the output goes is the user's: replacing it (a
// rename over it) or writing through it (to wherever it points, a loop or nowhere) would both do
// what the user did not ask. Links among the folders that hold the path are followed as usual.
template <typename Refuse>
void refuseLinkAtTheEnd(const std::string& path, const Refuse& refuse) {
  fs::path last = fs::path(path);
  // "a/link/" names what the link points to for the system, and the link for the user: checked.
  while (last.has_relative_path() && last.filename().empty()) last = last.parent_path();
  const std::string name = last.filename().string();
  if (name.empty() || name == "." || name == "..") return;
  std::error_code error;
  if (!fs::is_symlink(fs::symlink_status(last, error))) return;
  const fs::path target = fs::read_symlink(last, error);
  refuse("refused as an output: it is a symbolic link" +
         (error ? std::string() : " (to " + target.string() + ")") +
         ", which isg neither replaces nor writes through; remove it yourself or give another "
         "path");
}

}  // namespace

std::string describeOutput(OutputKind kind) { return infoOf(kind).description; }
bool isFolderOutput(OutputKind kind) { return infoOf(kind).folder; }

bool isWithin(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

fs::path resolvePath(const std::string& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = fs::path(path);
  fs::path resolved = fs::weakly_canonical(absolute, error);
  if (error) resolved = absolute.lexically_normal();
  // "a/b/" names the folder a/b.
  while (resolved.has_relative_path() && resolved.filename().empty()) {
    resolved = resolved.parent_path();
  }
  return resolved;
}

namespace {

fs::path checkOutputRule(const std::string& path, const OutputRule& rule) {
  const auto refuse = [&](const std::string& why) { throw common::InputError(path, "", why); };
  if (path.empty()) refuse("an empty output path");
  refuseLinkAtTheEnd(path, refuse);
  const fs::path resolved = resolvePath(path);
  const std::string what = describeOutput(rule.kind);
  if (resolved == resolved.root_path())
    refuse("refused as an output: it is the file system's root");
  const std::string cwd = currentDirectory();
  if (!cwd.empty() && resolved == fs::path(cwd)) {
    refuse("refused as an output: it is the working directory; give the name of " + what);
  }
  if (!cwd.empty() && isWithin(fs::path(cwd), resolved)) {
    refuse("refused as an output: it is " + resolved.string() +
           ", which holds the working directory");
  }
  for (const auto& input : rule.inputs) {
    if (input.empty()) continue;
    const fs::path in = resolvePath(input);
    if (in == resolved) refuse("refused as an output: it is the input " + input);
    if (isWithin(in, resolved)) refuse("refused as an output: it holds the input " + input);
    if (fs::is_directory(in) && isWithin(resolved, in)) {
      refuse("refused as an output: it lies inside the input folder " + input);
    }
  }
  std::error_code error;
  const fs::file_status status = fs::status(resolved, error);
  if (!fs::exists(status)) return resolved;
  if (isFolderOutput(rule.kind)) {
    if (!fs::is_directory(status)) refuse("exists and is not a folder; give " + what);
    if (rule.kind == OutputKind::kPictures) return resolved;
    if (rule.kind == OutputKind::kSweep) {
      if (mayHoldSweep(resolved)) return resolved;
      refuse(
          "holds files that are not an isg sweep's; give a new or empty folder, or a sweep "
          "folder");
    }
    if (!rule.replace) refuse("already exists (use --force to replace it)");
    const std::optional<OutputKind> found = folderOutputKind(resolved);
    if (!found) {
      refuse("not replaced: --force replaces only " + what +
             " that isg wrote, and this folder has no " + kOutputMarkerFile +
             " marker; remove it yourself or give another path");
    }
    if (*found != rule.kind) {
      refuse("not replaced: it is " + describeOutput(*found) + " of isg, not " + what);
    }
    return resolved;
  }
  if (fs::is_directory(status)) refuse("is a folder; give the name of " + what);
  if (!rule.replace) refuse("already exists (use --force to replace it)");
  if (!fs::is_regular_file(status) || !isOurFile(resolved, rule.kind)) {
    refuse(std::string("not replaced: it is not ") + what + " that isg wrote" +
           (rule.replace_needs_force ? " (--force replaces only those)" : "") +
           "; remove it yourself or give another path");
  }
  return resolved;
}

}  // namespace

fs::path checkOutputPath(const std::string& path, const OutputRule& rule) {
  const fs::path resolved = checkOutputRule(path, rule);
  // A folder the command adds to, when it exists, is written in rather than made or replaced.
  const bool adds_to_existing =
      (rule.kind == OutputKind::kSweep || rule.kind == OutputKind::kPictures) &&
      fs::is_directory(resolved);
  if (!adds_to_existing) requireParentFolder(path);
  return resolved;
}

void writeOutputMarker(const fs::path& folder, OutputKind kind) {
  const nlohmann::json marker = {{"written_by", "isg"}, {"kind", infoOf(kind).name}};
  const fs::path file = folder / kOutputMarkerFile;
  // Written beside and renamed over: a marker path that is a symlink is replaced, never followed.
  // The process's own temporary name: two writers at once never rename each other's file away.
  const fs::path temporary =
      folder / (std::string(kOutputMarkerFile) + ".tmp" + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << marker.dump() << "\n";
    out.flush();
    if (!out) {
      throw common::InputError(file.string(), "",
                               std::string("cannot write: ") + std::strerror(errno));
    }
  }
  std::error_code error;
  fs::rename(temporary, file, error);
  if (error) throw common::InputError(file.string(), "", "cannot write: " + error.message());
}

std::optional<OutputKind> folderOutputKind(const fs::path& folder) {
  const fs::path file = folder / kOutputMarkerFile;
  if (!fs::is_regular_file(file)) return std::nullopt;
  const nlohmann::json marker = nlohmann::json::parse(head(file, 4096), nullptr, false);
  if (!marker.is_object() || marker.value("written_by", "") != "isg") return std::nullopt;
  const std::string name = marker.value("kind", "");
  for (const auto& k : kKinds) {
    if (k.folder && name == k.name) return k.kind;
  }
  return std::nullopt;
}

bool isOurFile(const fs::path& path, OutputKind kind) {
  const std::string text = head(path, 8192);
  const std::string mark = kWrittenByIsg;
  switch (kind) {
    case OutputKind::kBag:
      return text.rfind("#ROSBAG V2.0\n", 0) == 0 && text.find(mark) != std::string::npos;
    case OutputKind::kMcap:  // the mark is in the Header's library field
      return text.rfind("\x89MCAP0\r\n", 0) == 0 && text.find(mark) != std::string::npos;
    case OutputKind::kPng:
      return text.rfind("\x89PNG", 0) == 0 &&
             text.find(std::string("tEXtSoftware\0", 13) + mark) != std::string::npos;
    case OutputKind::kSvg:
    case OutputKind::kMjcf:
    case OutputKind::kTableMarkdown:
      return text.find("<!-- " + mark) != std::string::npos;
    case OutputKind::kTableLatex:
      return text.rfind("% " + mark, 0) == 0;
    case OutputKind::kSubmission:
      return text.rfind("# " + mark, 0) == 0;
    case OutputKind::kBcf:  // the mark is in extensions.xml, the archive's second entry, stored
      return text.rfind("PK\x03\x04", 0) == 0 && text.find("<!-- " + mark) != std::string::npos;
    case OutputKind::kTableCsv:
      return text.rfind("world,", 0) == 0;
    case OutputKind::kAgraphJson:
      return text.find("\"format\": \"isg.agraph\"") != std::string::npos;
    case OutputKind::kImportedPlan:
      // A plan isg import wrote says where it came from; a plan a person wrote is never replaced.
      return text.find("\"format\": \"isg.plan\"") != std::string::npos &&
             text.find("\"imported_from\"") != std::string::npos;
    default:
      return false;
  }
}

std::string outputMark(OutputKind kind, const std::string& text) {
  const std::string mark = kWrittenByIsg;
  switch (kind) {
    case OutputKind::kSvg:
    case OutputKind::kMjcf:
    case OutputKind::kBcf: {
      // Inside the root element, after its start tag: the file still starts as its kind does
      // (tools that sniff "<svg" or "<mujoco" see it), and an XML declaration stays first.
      const std::size_t root = text.find_first_of('<', text.rfind("<?xml", 0) == 0 ? 2 : 0);
      const std::size_t end = root == std::string::npos ? root : text.find('>', root);
      if (end == std::string::npos) return text;
      return text.substr(0, end + 1) + "\n<!-- " + mark + " -->" + text.substr(end + 1);
    }
    case OutputKind::kTableMarkdown:
      return "<!-- " + mark + " -->\n" + text;
    case OutputKind::kTableLatex:
      return "% " + mark + "\n" + text;
    case OutputKind::kSubmission:  // TUM readers (evo's too) skip lines starting with '#'
      return "# " + mark + "\n" + text;
    default:
      return text;
  }
}

}  // namespace isg::common
