#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace isg::common {

// What a command writes. Folders of ours carry a marker file naming their kind; single files
// carry a mark in their own format (outputMark), so that --force, and the commands that replace
// their file when run again, never replace what isg did not write (docs/architecture.md,
// "Output paths").
enum class OutputKind {
  kRunFolder,   // isg run, isg slam
  kDataset,     // isg simulate
  kBuildings,   // isg generate
  kSweep,       // isg sweep (a folder the sweep adds to)
  kPictures,    // isg render (a folder its pictures are added to)
  kBag,         // isg export, isg simulate --rosbag
  kMcap,        // isg export --mcap, isg simulate --mcap
  kSvg,         // isg eval --plot, isg agraph --svg
  kPng,         // isg render's pictures
  kMjcf,        // isg world -o
  kAgraphJson,  // isg agraph -o
  kTableMarkdown,
  kTableCsv,
  kTableLatex,    // isg table -o
  kImportedPlan,  // isg import MODEL.ifc -o
  kSubmission,    // isg run --submission: a TUM file, marked by its first comment line
  kBcf,           // deviations.bcf (isg run, isg slam, isg bcf): a zip, marked in extensions.xml
};

// "a run folder", "a ROS bag", ...: what the messages call it.
std::string describeOutput(OutputKind kind);
bool isFolderOutput(OutputKind kind);

struct OutputRule {
  OutputKind kind = OutputKind::kRunFolder;
  // The files and folders the command reads: the output may not be one of them, hold one, or lie
  // inside an input folder.
  std::vector<std::string> inputs;
  // An existing output of ours of this kind may be replaced (--force, or a command that always
  // replaces its own file). Whatever else exists at the path is refused.
  bool replace = false;
  // Whether the user had to say --force for that (the message then suggests it).
  bool replace_needs_force = true;
};

// The one rule every command that writes follows: resolves `path` (absolute, symlinks of its
// existing part followed, no "." or ".." left) and refuses the working directory and its
// ancestors, the file system's root, the rule's inputs (and what holds them or lies in an input
// folder), a folder where a file is written and the reverse, and an existing path unless
// `rule.replace` and it is an output of ours of the same kind; and checks that it can be written
// (requireParentFolder: the nearest existing folder on its way may be written in). An InputError
// names `path` and says why. Returns the resolved path; nothing is touched.
std::filesystem::path checkOutputPath(const std::string& path, const OutputRule& rule);

// The marker file a folder output holds, and writing / reading it.
inline constexpr const char* kOutputMarkerFile = ".isg-output";
void writeOutputMarker(const std::filesystem::path& folder, OutputKind kind);
std::optional<OutputKind> folderOutputKind(const std::filesystem::path& folder);

// Whether the file at `path` is an output of ours of `kind` (its mark is there).
bool isOurFile(const std::filesystem::path& path, OutputKind kind);

// The text of a single-file output with its mark added where the format allows a comment (SVG,
// MJCF, Markdown, LaTeX); other kinds are returned as they are (a bag and a PNG are marked by
// their writers, an A-Graph and a CSV table are recognised by their header).
std::string outputMark(OutputKind kind, const std::string& text);

// The mark itself, for the writers that embed it (the bag's header padding, the PNG's text chunk).
inline constexpr const char* kWrittenByIsg = "written by isg";

// Whether `inner` is `outer` or lies inside it (both resolved).
bool isWithin(const std::filesystem::path& inner, const std::filesystem::path& outer);

// `path` made absolute and normal, symlinks of its existing part followed.
std::filesystem::path resolvePath(const std::string& path);

}  // namespace isg::common
