// The output-path rule (docs/architecture.md, "Output paths"), as an adversarial user tries it:
// every reproduction of the data-safety findings gives a clear error, exit 1, and every file
// beside, above and inside the refused path is still there afterwards.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Every regular file under `dir` with its content.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::error_code error;  // a symlink loop is no regular file, and no reason to throw
    if (!e.is_regular_file(error)) continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    files[fs::relative(e.path(), dir).string()] = text.str();
  }
  return files;
}

// A user's tree: s/keep/important, s/p/mine.txt, s/notes.txt.
void userTree(const testing::Sandbox& sandbox) {
  fs::create_directories(sandbox.dir() / "s/keep");
  fs::create_directories(sandbox.dir() / "s/p");
  sandbox.write("s/keep/important", "do not lose me\n");
  sandbox.write("s/p/mine.txt", "mine\n");
  sandbox.write("s/notes.txt", "notes\n");
}

TEST(OutputPaths, TheWorkingDirectoryAndItsAncestorsAreNeverAnOutput) {
  testing::Sandbox sandbox("out_cwd");
  userTree(sandbox);
  const auto before = snapshot(sandbox.dir());
  struct Case {
    std::string where, arguments, expected;
  };
  const std::vector<Case> cases = {
      {"s/p", "generate hall -o . --force -q",
       "isg generate: error: .: refused as an output: it is the working directory"},
      {"s/p", "generate hall -o ./ --force -q",
       "isg generate: error: ./: refused as an output: it is the working directory"},
      {"s", "run builtin:d1 --method odometry --duration 2 -o out/.. --force -q",
       "isg run: error: out/..: refused as an output: it is the working directory"},
      {"s/p", "run builtin:d1 --method odometry --duration 2 -o .. --force",
       "which holds the working directory"},
      {"s/p", "simulate builtin:d1 --duration 1 -o ../p --force -q",
       "isg simulate: error: ../p: refused as an output: it is the working directory"},
      {"s/p", "simulate builtin:d1 --duration 1 -o / --force -q", "it is the file system's root"},
      {"s/p", "render builtin:d1 -o .", "it is the working directory"},
  };
  for (const auto& c : cases) {
    const auto r = sandbox.run(c.arguments, c.where);
    EXPECT_EQ(r.exit_code, 1) << c.arguments << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.expected)) << c.arguments;
    EXPECT_EQ(snapshot(sandbox.dir()), before) << c.arguments;
    EXPECT_FALSE(fs::exists(sandbox.dir() / "s/out")) << c.arguments;
  }
}

TEST(OutputPaths, ForceReplacesOnlyAnOutputOfOursOfTheSameKind) {
  testing::Sandbox sandbox("out_force");
  userTree(sandbox);
  // A folder of the user's is not replaced by --force.
  const auto mine = sandbox.run("run builtin:d1 --method odometry --duration 2 -o s/keep --force");
  EXPECT_EQ(mine.exit_code, 1);
  EXPECT_THAT(mine.err,
              HasSubstr("s/keep: not replaced: --force replaces only a run folder that isg wrote, "
                        "and this folder has no .isg-output marker"));
  EXPECT_EQ(sandbox.read("s/keep/important"), "do not lose me\n");
  // One of ours of another kind is not either: a dataset is not a run folder.
  ASSERT_EQ(sandbox.run("simulate builtin:d1 --duration 1 -o ds -q").exit_code, 0);
  const auto other = sandbox.run("run builtin:d1 --method odometry --duration 2 -o ds --force");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err, HasSubstr("ds: not replaced: it is a dataset folder of isg, not a run "
                                   "folder"));
  EXPECT_TRUE(sandbox.exists("ds/imu.csv"));
  // One of ours of the same kind is, all at once, with its marker.
  ASSERT_EQ(sandbox.run("run builtin:d1 --method odometry --duration 2 -o r -q").exit_code, 0);
  EXPECT_THAT(sandbox.read("r/.isg-output"), HasSubstr("\"kind\":\"run\""));
  const auto again = sandbox.run("run builtin:d1 --method odometry --duration 3 -o r --force -q");
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(sandbox.read("r/metrics.json"), HasSubstr("\"sim_seconds\": 3"));
  // The input's own folder or files are never the output.
  fs::copy_file(fs::path(ISG_SOURCE_DIR) / "worlds/plans/d1.json", sandbox.dir() / "s/p/d1.json");
  const std::string plan = sandbox.read("s/p/d1.json");
  const auto self = sandbox.run("world s/p/d1.json -o s/p/d1.json");
  EXPECT_EQ(self.exit_code, 1);
  EXPECT_EQ(self.err,
            "isg world: error: s/p/d1.json: refused as an output: it is the input "
            "s/p/d1.json\n");
  const auto holder = sandbox.run("run s/p/d1.json --duration 2 -o s/p --force -q");
  EXPECT_EQ(holder.exit_code, 1);
  EXPECT_THAT(holder.err, HasSubstr("s/p: refused as an output: it holds the input s/p/d1.json"));
  EXPECT_EQ(sandbox.read("s/p/d1.json"), plan);
  EXPECT_EQ(sandbox.read("s/p/mine.txt"), "mine\n");
}

TEST(OutputPaths, AnExportNeverReplacesTheDatasetsOwnFilesOrAUsersFile) {
  testing::Sandbox sandbox("out_export");
  userTree(sandbox);
  ASSERT_EQ(sandbox.run("simulate builtin:d1 --duration 1 -o ds -q").exit_code, 0);
  const auto before = snapshot(sandbox.dir());
  const auto inside = sandbox.run("export ds --rosbag ds/imu.csv --force -q");
  EXPECT_EQ(inside.exit_code, 1);
  EXPECT_EQ(inside.err,
            "isg export: error: ds/imu.csv: refused as an output: it lies inside the input folder "
            "ds\n");
  const auto users = sandbox.run("export ds --rosbag s/notes.txt --force -q");
  EXPECT_EQ(users.exit_code, 1);
  EXPECT_THAT(users.err, HasSubstr("s/notes.txt: not replaced: it is not a ROS bag that isg "
                                   "wrote (--force replaces only those)"));
  const auto folder = sandbox.run("export ds --rosbag ds --force -q");
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_THAT(folder.err, HasSubstr("ds: refused as an output: it is the input ds"));
  EXPECT_EQ(snapshot(sandbox.dir()), before);
  // A bag of ours is replaced with --force.
  ASSERT_EQ(sandbox.run("export ds --rosbag b.bag -q").exit_code, 0);
  EXPECT_EQ(sandbox.run("export ds --rosbag b.bag -q").exit_code, 1);
  EXPECT_EQ(sandbox.run("export ds --rosbag b.bag --force -q").exit_code, 0);
}

// isg writes no symbolic links: one at the output path is the user's, never replaced (a dangling
// link became a regular file before) and never written through, with or without --force.
TEST(OutputPaths, ASymbolicLinkAtTheOutputIsNeverReplacedNorFollowed) {
  testing::Sandbox sandbox("out_links");
  userTree(sandbox);
  ASSERT_EQ(sandbox.run("simulate builtin:d1 --duration 1 -o ds -q").exit_code, 0);
  fs::create_symlink("nowhere.bag", sandbox.dir() / "dangling.bag");
  fs::create_symlink("loop.mcap", sandbox.dir() / "loop.mcap");
  fs::create_symlink("s/keep", sandbox.dir() / "kept");
  fs::create_symlink("notes.txt", sandbox.dir() / "s/p/plan.png");
  const auto before = snapshot(sandbox.dir());
  const std::string link =
      ", which isg neither replaces nor writes through; remove it yourself or give another path\n";
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {"export ds --rosbag dangling.bag -q",
       "isg export: error: dangling.bag: refused as an output: it is a symbolic link (to "
       "nowhere.bag)" +
           link},
      {"export ds --rosbag dangling.bag --force -q",
       "isg export: error: dangling.bag: refused as an output: it is a symbolic link (to "
       "nowhere.bag)" +
           link},
      {"export ds --mcap loop.mcap -q",
       "isg export: error: loop.mcap: refused as an output: it is a symbolic link (to "
       "loop.mcap)" +
           link},
      {"run builtin:d1 --method odometry --duration 1 -o kept --force -q",
       "isg run: error: kept: refused as an output: it is a symbolic link (to s/keep)" + link},
      {"simulate builtin:d1 --duration 1 -o kept/ --force -q",
       "isg simulate: error: kept/: refused as an output: it is a symbolic link (to s/keep)" +
           link},
      {"world builtin:d1 -o dangling.bag",
       "isg world: error: dangling.bag: refused as an output: it is a symbolic link (to "
       "nowhere.bag)" +
           link},
      {"render builtin:d1 -o s/p --width 64 --height 48",
       "isg render: error: s/p/plan.png: refused as an output: it is a symbolic link (to "
       "notes.txt)" +
           link},
  };
  for (const auto& c : cases) {
    const auto r = sandbox.run(c.arguments);
    EXPECT_EQ(r.exit_code, 1) << c.arguments;
    EXPECT_EQ(r.err, c.expected) << c.arguments;
  }
  EXPECT_EQ(snapshot(sandbox.dir()), before);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(sandbox.dir() / "dangling.bag")));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(sandbox.dir() / "loop.mcap")));
  EXPECT_FALSE(fs::exists(sandbox.dir() / "nowhere.bag"));
}

// Every output is checked before anything is made: a command that fails leaves none of the
// folders its output paths would have needed.
TEST(OutputPaths, AFailedCommandLeavesNoFoldersBehind) {
  testing::Sandbox sandbox("out_no_folders");
  userTree(sandbox);
  ASSERT_EQ(sandbox.run("simulate builtin:d1 --duration 1 -o ds -q").exit_code, 0);
  const auto before = snapshot(sandbox.dir());
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {"run builtin:d1 --duration 1 -o np3/a/b/c/run --mcap s/notes.txt/x.mcap -q",
       "isg run: error: s/notes.txt/x.mcap: cannot write: s/notes.txt is not a directory\n"},
      {"run builtin:d1 --duration 1 -o np3/a/run --mcap s/notes.txt -q",
       "isg run: error: s/notes.txt: already exists (use --force to replace it)\n"},
      {"run builtin:d1 --duration 1 -o s/notes.txt/run -q",
       "isg run: error: s/notes.txt/run: cannot write: s/notes.txt is not a directory\n"},
      {"simulate builtin:d1 --duration 1 -o np4/a/ds --rosbag s/notes.txt --force -q",
       "isg simulate: error: s/notes.txt: not replaced: it is not a ROS bag that isg wrote "
       "(--force replaces only those); remove it yourself or give another path\n"},
      {"slam ds --method odometry -o np5/a/run --mcap s/notes.txt/x.mcap -q",
       "isg slam: error: s/notes.txt/x.mcap: cannot write: s/notes.txt is not a directory\n"},
      {"export ds --rosbag np6/a/b.bag --mcap s/notes.txt/x.mcap -q",
       "isg export: error: s/notes.txt/x.mcap: cannot write: s/notes.txt is not a directory\n"},
  };
  for (const auto& c : cases) {
    const auto r = sandbox.run(c.arguments);
    EXPECT_EQ(r.exit_code, 1) << c.arguments;
    EXPECT_EQ(r.err, c.expected) << c.arguments;
  }
  EXPECT_EQ(snapshot(sandbox.dir()), before);
  for (const char* folder : {"np3", "np4", "np5", "np6"}) EXPECT_FALSE(sandbox.exists(folder));
  // Made when the outputs are written.
  const auto deep =
      sandbox.run("run builtin:d1 --duration 1 -o deep/a/run --mcap deep/b/r.mcap -q");
  EXPECT_EQ(deep.exit_code, 0) << deep.err;
  EXPECT_TRUE(sandbox.exists("deep/a/run/metrics.json"));
  EXPECT_TRUE(sandbox.exists("deep/b/r.mcap"));
}

TEST(OutputPaths, SingleFileOutputsReplaceOnlyTheirOwnFiles) {
  testing::Sandbox sandbox("out_files");
  userTree(sandbox);
  // isg world, isg agraph, isg table and isg eval --plot replace their own earlier file when run
  // again, and nothing else.
  ASSERT_EQ(sandbox.run("world builtin:d1 -o w.xml").exit_code, 0);
  EXPECT_EQ(sandbox.run("world builtin:d1 -o w.xml").exit_code, 0);
  const auto world = sandbox.run("world builtin:d1 -o s/notes.txt");
  EXPECT_EQ(world.exit_code, 1);
  EXPECT_THAT(world.err, HasSubstr("s/notes.txt: not replaced: it is not an MJCF world that isg "
                                   "wrote; remove it yourself or give another path"));
  ASSERT_EQ(sandbox.run("agraph builtin:d1 -o a.json --svg a.svg").exit_code, 0);
  EXPECT_EQ(sandbox.run("agraph builtin:d1 -o a.json --svg a.svg").exit_code, 0);
  EXPECT_EQ(sandbox.run("agraph builtin:d1 --svg s/notes.txt").exit_code, 1);
  ASSERT_EQ(sandbox.run("run builtin:d1 --method odometry --duration 2 -o r -q").exit_code, 0);
  for (const char* format : {"md", "csv", "latex"}) {
    const std::string out = std::string("t.") + format;
    ASSERT_EQ(sandbox.run("table r --format " + std::string(format) + " -o " + out).exit_code, 0);
    EXPECT_EQ(sandbox.run("table r --format " + std::string(format) + " -o " + out).exit_code, 0)
        << format;
    EXPECT_EQ(sandbox.run("table r --format " + std::string(format) + " -o s/notes.txt").exit_code,
              1);
  }
  EXPECT_EQ(sandbox.run("table r -o r/metrics.json").exit_code, 1);  // an input's own file
  ASSERT_EQ(sandbox.run("eval r/groundtruth.tum r/odometry.tum --plot p.svg").exit_code, 0);
  EXPECT_EQ(sandbox.run("eval r/groundtruth.tum r/odometry.tum --plot p.svg").exit_code, 0);
  EXPECT_EQ(sandbox.run("eval r/groundtruth.tum r/odometry.tum --plot r/odometry.tum").exit_code,
            1);
  // isg render adds its pictures to a folder, replacing only pictures of its own (PNG text chunk).
  ASSERT_EQ(sandbox.run("render builtin:d1 -o pics --width 64 --height 48").exit_code, 0);
  EXPECT_EQ(sandbox.run("render builtin:d1 -o pics --width 64 --height 48").exit_code, 0);
  sandbox.write("s/top.png", "a picture of the user's\n");
  const auto render = sandbox.run("render builtin:d1 -o s --width 64 --height 48");
  EXPECT_EQ(render.exit_code, 1);
  EXPECT_THAT(render.err, HasSubstr("s/top.png: not replaced: it is not a PNG picture that isg "
                                    "wrote"));
  EXPECT_FALSE(sandbox.exists("s/plan.png"));
  EXPECT_EQ(sandbox.read("s/top.png"), "a picture of the user's\n");
  EXPECT_EQ(sandbox.read("s/notes.txt"), "notes\n");
  EXPECT_EQ(sandbox.read("s/keep/important"), "do not lose me\n");
}

}  // namespace
}  // namespace isg::cli
