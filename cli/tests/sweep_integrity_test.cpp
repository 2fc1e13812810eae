// A sweep's results are never mixed: one sweep at a time in a folder, a world edited between two
// starts refused (or re-run), damaged and foreign cells moved aside and re-run, stale failure
// records cleared, and tables that count every seed the suite asked for.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

std::string plansDir() { return std::string(ISG_SOURCE_DIR) + "/worlds/plans/"; }

// A suite of the file world w.json (and more worlds), odometry for 2 s: fast cells.
std::string suiteOf(const std::string& worlds, const std::string& seeds = "[1, 2]") {
  return R"({"format": "isg.suite", "version": 1, "name": "t", "worlds": )" + worlds +
         R"(, "seeds": )" + seeds + R"(, "methods": ["odometry"], "run": {"duration": 2}})";
}

std::string metricsHash(const testing::Sandbox& sandbox, const std::string& cell) {
  return nlohmann::json::parse(sandbox.read(cell + "/metrics.json")).value("world_hash", "");
}

TEST(SweepIntegrity, ASecondSweepIntoOneFolderIsRefusedNamingTheHolder) {
  testing::Sandbox sandbox("sweep_lock");
  sandbox.write("suite.json", suiteOf(R"(["builtin:d1"])", "[1]"));
  ASSERT_EQ(sandbox.run("sweep suite.json -o out -q").exit_code, 0);
  // This process holds the lock, as a running sweep does.
  const int fd = ::open((sandbox.dir() / "out/.lock").c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const std::string pid = std::to_string(::getpid()) + "\n";
  ASSERT_EQ(::ftruncate(fd, 0), 0);
  ASSERT_EQ(::pwrite(fd, pid.data(), pid.size(), 0), ssize_t(pid.size()));
  const auto second = sandbox.run("sweep suite.json -o out -q");
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_THAT(second.err, HasSubstr("out: another isg sweep is running in this folder (pid " +
                                    std::to_string(::getpid()) + ")"));
  ::close(fd);  // the holder ends: the lock goes with it
  EXPECT_EQ(sandbox.run("sweep suite.json -o out -q").exit_code, 0);
}

// Two real sweeps at once into one folder: the second is refused while the first runs, and the
// first finishes every cell once.
TEST(SweepIntegrity, TwoSweepsAtOnceOneIsRefused) {
  testing::Sandbox sandbox("sweep_two");
  sandbox.write("suite.json", suiteOf(R"(["builtin:d1", "builtin:d2"])", "[1, 2, 3]"));
  const pid_t first = ::fork();
  ASSERT_GE(first, 0);
  if (first == 0) {
    if (::chdir(sandbox.dir().c_str()) != 0) ::_exit(126);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(ISG_EXECUTABLE, "isg", "sweep", "suite.json", "-o", "out", "-q", nullptr);
    ::_exit(127);
  }
  // Until the first holds the lock (its pid in the lock file).
  const std::string pid = std::to_string(first);
  for (int i = 0; i < 600 && sandbox.read("out/.lock") != pid + "\n"; ++i) {
    ::usleep(10000);
  }
  ASSERT_EQ(sandbox.read("out/.lock"), pid + "\n");
  const auto second = sandbox.run("sweep suite.json -o out -q");
  int status = 0;
  ::waitpid(first, &status, 0);
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_THAT(second.err, HasSubstr("another isg sweep is running in this folder (pid " + pid));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_FALSE(fs::exists(sandbox.dir() / "out/d1/odometry/seed-1.failed.json"));
  const auto again = sandbox.run("sweep suite.json -o out");
  EXPECT_THAT(again.err, HasSubstr("6 of 6 cells finished before; running the other 0"));
}

// Sweeps started at the same instant into a new folder: one runs, every other is told so (never
// "cannot write" of a marker another one renamed away), in every round. On a loaded machine the
// scheduler may start one only after the first has ended (the cell takes about a second): that one
// finds the cell finished and runs nothing, which is right too; never does a second one run it.
TEST(SweepIntegrity, SweepsStartedAtTheSameInstantOneRunsTheOthersAreToldSo) {
  testing::Sandbox sandbox("sweep_instant");
  sandbox.write("suite.json", suiteOf(R"(["builtin:d1"])", "[1]"));
  constexpr int kRounds = 4, kSweeps = 3;
  for (int round = 0; round < kRounds; ++round) {
    const std::string out = "out" + std::to_string(round);
    int gate[2];
    ASSERT_EQ(::pipe(gate), 0);
    std::vector<pid_t> children;
    for (int k = 0; k < kSweeps; ++k) {
      const std::string err = out + "-" + std::to_string(k) + ".err";
      const pid_t child = ::fork();
      ASSERT_GE(child, 0);
      if (child == 0) {
        ::close(gate[1]);
        char byte;
        while (::read(gate[0], &byte, 1) > 0) {
        }  // released when the parent closes its end: all at once
        if (::chdir(sandbox.dir().c_str()) != 0) ::_exit(126);
        const int null = ::open("/dev/null", O_WRONLY);
        const int errors = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(null, 1);
        ::dup2(errors, 2);
        ::execl(ISG_EXECUTABLE, "isg", "sweep", "suite.json", "-o", out.c_str(), nullptr);
        ::_exit(127);
      }
      children.push_back(child);
    }
    ::close(gate[0]);
    ::close(gate[1]);
    int ran = 0;
    for (int k = 0; k < kSweeps; ++k) {
      int status = 0;
      ::waitpid(children[std::size_t(k)], &status, 0);
      ASSERT_TRUE(WIFEXITED(status));
      const std::string err = sandbox.read(out + "-" + std::to_string(k) + ".err");
      if (WEXITSTATUS(status) == 0) {
        // Started after the one that ran it had ended: nothing left to run.
        const bool found_finished =
            err.find("1 of 1 cell finished before; running the other 0") != std::string::npos;
        ran += found_finished ? 0 : 1;
        continue;
      }
      EXPECT_EQ(WEXITSTATUS(status), 1) << err;
      EXPECT_THAT(err, HasSubstr("isg sweep: error: " + out +
                                 ": another isg sweep is running in this folder (pid "))
          << "round " << round;
    }
    EXPECT_EQ(ran, 1) << "round " << round;
    EXPECT_TRUE(sandbox.exists(out + "/d1/odometry/seed-1/metrics.json"));
  }
}

TEST(SweepIntegrity, AWorldEditedBetweenTwoStartsIsRefusedOrRunAgainNeverMixed) {
  testing::Sandbox sandbox("sweep_changed");
  fs::copy_file(plansDir() + "d1.json", sandbox.dir() / "w.json");
  sandbox.write("suite.json", suiteOf(R"(["w.json"])"));
  ASSERT_EQ(sandbox.run("sweep suite.json -o out -q").exit_code, 0);
  const std::string first_hash = metricsHash(sandbox, "out/w/odometry/seed-1");
  ASSERT_EQ(first_hash.rfind("sha256:", 0), 0u);
  const nlohmann::json plan = nlohmann::json::parse(sandbox.read("out/sweep.json"));
  EXPECT_EQ(plan["worlds"][0]["hash"], first_hash);
  // Interrupted after one cell (the other's folder gone), then the world file replaced.
  fs::remove_all(sandbox.dir() / "out/w/odometry/seed-2");
  fs::copy_file(plansDir() + "d2.json", sandbox.dir() / "w.json",
                fs::copy_options::overwrite_existing);
  const std::string metrics = sandbox.read("out/w/odometry/seed-1/metrics.json");
  const auto refused = sandbox.run("sweep suite.json -o out -q");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, HasSubstr("world changed since this sweep ran in out: w (sha256:"));
  EXPECT_THAT(refused.err, HasSubstr("--rerun-changed"));
  EXPECT_EQ(sandbox.read("out/w/odometry/seed-1/metrics.json"), metrics);
  EXPECT_FALSE(sandbox.exists("out/w/odometry/seed-2"));
  // Re-run on the world as it is now: every cell of it, the old ones kept aside.
  const auto rerun = sandbox.run("sweep suite.json -o out -q --rerun-changed");
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_THAT(rerun.err, HasSubstr("w/odometry/seed-1 ran on the world before it changed; moved "
                                   "to .aside/w/odometry/seed-1"));
  EXPECT_EQ(sandbox.read("out/.aside/w/odometry/seed-1/metrics.json"), metrics);
  const std::string now = metricsHash(sandbox, "out/w/odometry/seed-1");
  EXPECT_NE(now, first_hash);
  EXPECT_EQ(metricsHash(sandbox, "out/w/odometry/seed-2"), now);
  EXPECT_THAT(rerun.out, HasSubstr("2 of 2 cells finished"));
}

TEST(SweepIntegrity, AChangedGeneratorSpecIsAChangedWorld) {
  testing::Sandbox sandbox("sweep_spec");
  const auto spec = [](int rooms) {
    return R"([{"generate": {"family": "office", "rooms": )" + std::to_string(rooms) + "}}]";
  };
  sandbox.write("suite.json", suiteOf(spec(6), "[1]"));
  ASSERT_EQ(sandbox.run("sweep suite.json -o out -q").exit_code, 0);
  const std::string six = sandbox.read("out/worlds/office-1.json");
  sandbox.write("suite.json", suiteOf(spec(10), "[1]"));
  const auto refused = sandbox.run("sweep suite.json -o out -q");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, HasSubstr("changed since this sweep ran in out: office-1"));
  const auto rerun = sandbox.run("sweep suite.json -o out -q --rerun-changed");
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_NE(sandbox.read("out/worlds/office-1.json"), six);  // the world of the spec as it is now
  const nlohmann::json plan = nlohmann::json::parse(sandbox.read("out/sweep.json"));
  EXPECT_EQ(plan["worlds"][0]["generate"]["rooms"], 10);
  EXPECT_EQ(plan["worlds"][0]["hash"], metricsHash(sandbox, "out/office-1/odometry/seed-1"));
}

TEST(SweepIntegrity, DamagedAndForeignCellsAreMovedAsideAndRunAgain) {
  testing::Sandbox sandbox("sweep_damaged");
  sandbox.write("suite.json", suiteOf(R"(["builtin:d1", "builtin:d2"])"));
  ASSERT_EQ(sandbox.run("sweep suite.json -o out -q").exit_code, 0);
  const std::string good = sandbox.read("out/d1/odometry/seed-2/metrics.json");
  const std::string d1_seed1 = sandbox.read("out/d1/odometry/seed-1/metrics.json");
  // Truncated, deleted, and copied from another world's cell.
  sandbox.write("out/d1/odometry/seed-1/metrics.json", good.substr(0, good.size() / 2));
  fs::remove(sandbox.dir() / "out/d1/odometry/seed-2/metrics.json");
  const std::string other = sandbox.read("out/d1/odometry/seed-1/odometry.tum");
  sandbox.write("out/d2/odometry/seed-1/metrics.json", d1_seed1);
  // A stale failure record beside a finished cell (a second sweep's, before the lock).
  sandbox.write("out/d2/odometry/seed-2.failed.json", R"({"error": ["old"]})");

  // --collect reads the folder whole: the damaged cells are counted, never a number.
  const auto collect = sandbox.run("sweep --collect out");
  EXPECT_EQ(collect.exit_code, 5);
  EXPECT_THAT(collect.out, HasSubstr("failed: d1/odometry/seed-1: not a finished run of this "
                                     "cell ("));
  EXPECT_THAT(collect.out, HasSubstr("failed: d1/odometry/seed-2: not a finished run of this cell "
                                     "(out/d1/odometry/seed-2: not a run folder (no "
                                     "metrics.json))"));
  EXPECT_THAT(collect.out, HasSubstr("failed: d2/odometry/seed-1: not a finished run of this cell "
                                     "(it ran on another world"));
  EXPECT_THAT(collect.out, HasSubstr("1 of 4 cells finished, 3 failed, 0 not run"));
  EXPECT_THAT(sandbox.read("out/table.md"), HasSubstr("| d1 | 0/2, 2 failed |"));

  const auto repaired = sandbox.run("sweep suite.json -o out -q");
  ASSERT_EQ(repaired.exit_code, 0) << repaired.err;
  EXPECT_THAT(repaired.err, HasSubstr("d1/odometry/seed-1: "));
  EXPECT_THAT(repaired.err, HasSubstr("moved to .aside/d1/odometry/seed-1, running it again"));
  EXPECT_THAT(repaired.err, HasSubstr("moved to .aside/d2/odometry/seed-1, running it again"));
  EXPECT_EQ(sandbox.read("out/.aside/d1/odometry/seed-1/odometry.tum"), other);
  EXPECT_THAT(repaired.out, HasSubstr("4 of 4 cells finished, 0 failed, 0 not run"));
  EXPECT_FALSE(sandbox.exists("out/d2/odometry/seed-2.failed.json"));
  // The documented glob reads every cell again.
  const auto table = sandbox.run("table out/*/*/seed-* --format csv");
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_EQ(table.out, sandbox.read("out/table.csv"));
}

TEST(SweepIntegrity, ATableCountsTheSuitesSeedsFailedAndMissingOnesSaid) {
  testing::Sandbox sandbox("sweep_partial");
  // max_array_size given: the dry run asks no Slurm controller.
  std::string suite = suiteOf(R"(["builtin:d2"])", "[1, 2, 3]");
  suite.insert(suite.size() - 1, R"(, "slurm": {"max_array_size": 100})");
  sandbox.write("suite.json", suite);
  // Written, not run (the Slurm backend's dry run), then one cell run, one failed.
  ASSERT_EQ(sandbox.run("sweep suite.json -o out --backend slurm --dry-run -q").exit_code, 0);
  ASSERT_EQ(sandbox.run("sweep out --cell 0 -q").exit_code, 0);
  sandbox.write("out/d2/odometry/seed-2.failed.json",
                R"({"world": "d2", "method": "odometry", "seed": 2, )"
                R"("error": ["isg run: error: No space left on device"]})");
  const auto collect = sandbox.run("sweep --collect out");
  EXPECT_EQ(collect.exit_code, 5);
  const std::string md = sandbox.read("out/table.md");
  EXPECT_THAT(md, HasSubstr(" 1/3, 1 failed, 1 not run |"));
  EXPECT_THAT(md, HasSubstr("| *localized correctly* | 0/1 |"));  // never "every seed"
  EXPECT_THAT(md, HasSubstr("n counts the suite's seeds"));
  EXPECT_THAT(sandbox.read("out/table.csv"), HasSubstr("odometry: failed,odometry: not run"));
  // The documented glob matches the failure record too: isg table counts it as a failed seed.
  const auto table = sandbox.run("table out/*/*/seed-*");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr(" 1/2, 1 failed |"));
}

TEST(SweepIntegrity, IsgTableNeverMergesDifferentWorldsOfOneName) {
  testing::Sandbox sandbox("table_worlds");
  fs::create_directories(sandbox.dir() / "a");
  fs::create_directories(sandbox.dir() / "b");
  fs::copy_file(plansDir() + "d1.json", sandbox.dir() / "a/w.json");
  fs::copy_file(plansDir() + "d2.json", sandbox.dir() / "b/w.json");
  ASSERT_EQ(sandbox.run("run w.json --method odometry --duration 2 -o r -q", "a").exit_code, 0);
  ASSERT_EQ(sandbox.run("run w.json --method odometry --duration 2 -o r -q", "b").exit_code, 0);
  const auto table = sandbox.run("table a/r b/r");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const std::string a = metricsHash(sandbox, "a/r").substr(7, 8);
  const std::string b = metricsHash(sandbox, "b/r").substr(7, 8);
  EXPECT_THAT(table.out, HasSubstr("| w.json [" + a + "] |"));
  EXPECT_THAT(table.out, HasSubstr("| w.json [" + b + "] |"));
  EXPECT_THAT(table.out, HasSubstr("different buildings of one name"));
  // The same building under two paths is one world.
  fs::create_directories(sandbox.dir() / "c");
  fs::copy_file(plansDir() + "d1.json", sandbox.dir() / "c/w.json");
  ASSERT_EQ(
      sandbox.run("run w.json --method odometry --duration 2 --seed 2 -o r -q", "c").exit_code, 0);
  const auto same = sandbox.run("table a/r c/r");
  EXPECT_THAT(same.out, HasSubstr("| w.json | "));
  EXPECT_THAT(same.out, Not(HasSubstr("w.json [")));
}

}  // namespace
}  // namespace isg::cli
