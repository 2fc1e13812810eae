// The output-path rule on its own (common/output_path): what an output may never be, and what an
// existing path must be to be replaced. Every command's use of it is cli/tests/output_paths_test's.
#include "common/output_path.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"

namespace isg::common {
namespace {

namespace fs = std::filesystem;

class OutputPath : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("isg_output_path_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "work");
    before_ = fs::current_path();
    fs::current_path(root_ / "work");
  }
  void TearDown() override {
    fs::current_path(before_);
    fs::remove_all(root_);
  }
  // Why checkOutputPath refuses `path`, or "" when it accepts it.
  std::string refusal(const std::string& path, const OutputRule& rule) {
    try {
      checkOutputPath(path, rule);
      return "";
    } catch (const InputError& e) {
      return e.reason();
    }
  }
  fs::path root_, before_;
};

TEST_F(OutputPath, NeverTheWorkingDirectoryNorWhatHoldsIt) {
  const OutputRule run{OutputKind::kRunFolder, {}, true};
  EXPECT_EQ(refusal(".", run),
            "refused as an output: it is the working directory; give the name of a run folder");
  EXPECT_EQ(refusal("./", run), refusal(".", run));
  EXPECT_EQ(refusal("x/..", run), refusal(".", run));
  EXPECT_EQ(refusal("..", run), "refused as an output: it is " + root_.string() +
                                    ", which holds the working directory");
  EXPECT_EQ(refusal("/", run), "refused as an output: it is the file system's root");
  EXPECT_EQ(refusal("", run), "an empty output path");
  EXPECT_EQ(refusal("runs/new", run), "");  // a new path
}

TEST_F(OutputPath, NeverAnInputNorWhatHoldsOneNorAPathInsideOne) {
  fs::create_directories("ds");
  std::ofstream("plan.json") << "{}";
  const OutputRule bag{OutputKind::kBag, {"ds"}, true};
  EXPECT_EQ(refusal("ds", bag), "refused as an output: it is the input ds");
  EXPECT_EQ(refusal("ds/out.bag", bag), "refused as an output: it lies inside the input folder ds");
  const OutputRule run{OutputKind::kRunFolder, {"sub/plan.json"}, true};
  fs::create_directories("sub");
  std::ofstream("sub/plan.json") << "{}";
  EXPECT_EQ(refusal("sub", run), "refused as an output: it holds the input sub/plan.json");
}

TEST_F(OutputPath, AnExistingFolderIsReplacedOnlyWhenIsgWroteItOfTheSameKind) {
  fs::create_directories("mine");
  std::ofstream("mine/notes.txt") << "the user's";
  const OutputRule forced{OutputKind::kRunFolder, {}, true};
  EXPECT_EQ(refusal("mine", forced),
            "not replaced: --force replaces only a run folder that isg wrote, and this folder has "
            "no .isg-output marker; remove it yourself or give another path");
  fs::create_directories("old_run");
  writeOutputMarker("old_run", OutputKind::kRunFolder);
  EXPECT_EQ(folderOutputKind("old_run"), OutputKind::kRunFolder);
  EXPECT_EQ(refusal("old_run", forced), "");
  EXPECT_EQ(refusal("old_run", {OutputKind::kRunFolder, {}, false}),
            "already exists (use --force to replace it)");
  EXPECT_EQ(refusal("old_run", {OutputKind::kDataset, {}, true}),
            "not replaced: it is a run folder of isg, not a dataset folder");
  std::ofstream("file") << "x";
  EXPECT_EQ(refusal("file", forced), "exists and is not a folder; give a run folder");
}

TEST_F(OutputPath, AnExistingFileIsReplacedOnlyWhenItCarriesOurMark) {
  std::ofstream("theirs.svg") << "<svg/>";
  const OutputRule svg{OutputKind::kSvg, {}, true, false};
  EXPECT_EQ(refusal("theirs.svg", svg),
            "not replaced: it is not an SVG picture that isg wrote; remove it yourself or give "
            "another path");
  // The mark goes inside the root element, after its start tag.
  std::ofstream("ours.svg") << outputMark(OutputKind::kSvg, "<svg></svg>");
  EXPECT_TRUE(isOurFile("ours.svg", OutputKind::kSvg));
  EXPECT_FALSE(isOurFile("theirs.svg", OutputKind::kSvg));
  EXPECT_EQ(refusal("ours.svg", svg), "");
  fs::create_directories("folder.svg");
  EXPECT_EQ(refusal("folder.svg", svg), "is a folder; give the name of an SVG picture");
}

TEST_F(OutputPath, ASymbolicLinkIsNeverReplacedNorWrittenThrough) {
  const std::string link =
      ", which isg neither replaces nor writes through; remove it yourself or give another path";
  const OutputRule bag{OutputKind::kBag, {}, true};
  fs::create_symlink("nowhere.bag", "dangling.bag");
  EXPECT_EQ(refusal("dangling.bag", bag),
            "refused as an output: it is a symbolic link (to nowhere.bag)" + link);
  fs::create_symlink("loop.bag", "loop.bag");
  EXPECT_EQ(refusal("loop.bag", bag),
            "refused as an output: it is a symbolic link (to loop.bag)" + link);
  // To a bag of ours: still the user's link.
  std::ofstream("ours.bag") << "#ROSBAG V2.0\n" << kWrittenByIsg;
  ASSERT_TRUE(isOurFile("ours.bag", OutputKind::kBag));
  fs::create_symlink("ours.bag", "latest.bag");
  EXPECT_EQ(refusal("latest.bag", bag),
            "refused as an output: it is a symbolic link (to ours.bag)" + link);
  EXPECT_EQ(refusal("ours.bag", bag), "");
  // A link to a folder, with or without a trailing separator; links above the last part are
  // followed as always.
  const OutputRule run{OutputKind::kRunFolder, {}, true};
  fs::create_directories("real/runs");
  fs::create_symlink("real/runs", "runs");
  EXPECT_EQ(refusal("runs", run),
            "refused as an output: it is a symbolic link (to real/runs)" + link);
  EXPECT_EQ(refusal("runs/", run), refusal("runs", run));
  EXPECT_EQ(refusal("runs/new", run), "");
  EXPECT_EQ(checkOutputPath("runs/new", run), root_ / "work/real/runs/new");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status("dangling.bag")));
  EXPECT_FALSE(fs::exists("nowhere.bag"));
}

TEST_F(OutputPath, AFolderWrittenAtomicallyIsOursAndComplete) {
  writeFolderAtomically("made", OutputKind::kDataset, false, [](const fs::path& temporary) {
    std::ofstream(temporary / "a.txt") << "a";
  });
  EXPECT_EQ(folderOutputKind("made"), OutputKind::kDataset);
  EXPECT_TRUE(fs::is_regular_file("made/a.txt"));
  // A failure leaves nothing behind, and an existing output of ours as it was.
  EXPECT_THROW(writeFolderAtomically("made", OutputKind::kDataset, true,
                                     [](const fs::path&) { throw InputError("x", "", "boom"); }),
               InputError);
  EXPECT_TRUE(fs::is_regular_file("made/a.txt"));
  for (const auto& entry : fs::directory_iterator(".")) {
    EXPECT_EQ(entry.path().filename().string().find(".made.partial"), std::string::npos);
  }
}

TEST_F(OutputPath, MissingFoldersAreMadeOnlyForAWriteThatSucceeds) {
  // A failed write leaves none of the folders it made; a folder written into meanwhile stays.
  EXPECT_THROW(writeFolderAtomically("a/b/c/run", OutputKind::kRunFolder, false,
                                     [](const fs::path&) { throw InputError("x", "", "boom"); }),
               InputError);
  EXPECT_FALSE(fs::exists("a"));
  EXPECT_THROW(writeFolderAtomically("a/b/run", OutputKind::kRunFolder, false,
                                     [](const fs::path&) {
                                       std::ofstream("a/mine.txt") << "mine";
                                       throw InputError("x", "", "boom");
                                     }),
               InputError);
  EXPECT_TRUE(fs::is_regular_file("a/mine.txt"));
  EXPECT_FALSE(fs::exists("a/b"));
  {
    AtomicFile uncommitted("d/e/x.bag", OutputKind::kBag, false);
    EXPECT_TRUE(fs::is_directory("d/e"));
  }
  EXPECT_FALSE(fs::exists("d"));
  // The probe before the work makes and removes them again.
  checkCanCreateFolder("p/q/run", OutputKind::kRunFolder, false);
  EXPECT_FALSE(fs::exists("p"));
  // A write that succeeds keeps them.
  writeFolderAtomically("a/b/run", OutputKind::kRunFolder, false,
                        [](const fs::path& temporary) { std::ofstream(temporary / "x") << "x"; });
  writeFileAtomically("f/g/plot.svg", "<svg/>");
  EXPECT_TRUE(fs::is_regular_file("a/b/run/x"));
  EXPECT_TRUE(fs::is_regular_file("f/g/plot.svg"));
  // What cannot be made is said at once, naming the part that is not a folder.
  std::ofstream("file") << "x";
  try {
    checkCanCreateFolder("file/a/run", OutputKind::kRunFolder, false);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.reason(), "cannot write: file is not a directory");
  }
}

TEST_F(OutputPath, AFileWrittenInPartsIsThePartsInOrder) {
  // A run's long TUM files are written 8192 poses at a time: the file is the parts, in order.
  int given = 0;
  writeFileInParts("parts.txt", [&] { return given < 3 ? std::to_string(given++) + "\n" : ""; });
  std::ifstream in("parts.txt");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "0\n1\n2\n");
  writeFileInParts("empty.txt", [] { return std::string(); });
  EXPECT_TRUE(fs::exists("empty.txt"));
  EXPECT_EQ(fs::file_size("empty.txt"), 0u);
  // A write that fails names the file and says why.
  if (fs::exists("/dev/full")) {
    try {
      writeFileInParts("/dev/full", [n = 0]() mutable {
        return n++ < 1000 ? std::string(1 << 16, 'x') : std::string();
      });
      ADD_FAILURE() << "a full device took the file";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace isg::common
