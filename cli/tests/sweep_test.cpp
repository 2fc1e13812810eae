#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string suite(const std::string& worlds, const std::string& seeds, const std::string& methods,
                  const std::string& run) {
  return R"({"format": "isg.suite", "version": 1, "name": "t", "worlds": )" + worlds +
         R"(, "seeds": )" + seeds + R"(, "methods": )" + methods + R"(, "run": )" + run + "}";
}

int countFiles(const fs::path& dir, const std::string& name) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    n += e.path().filename() == name;
  }
  return n;
}

bool anyPartial(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().filename().string().find(".partial") != std::string::npos) return true;
  }
  return false;
}

// Two worlds × two seeds × two methods on two processes; the collected table is isg table's of
// the same run folders; started again, nothing is run twice.
TEST(Sweep, RunsEveryCellAndTabulatesAsIsgTable) {
  testing::Sandbox sandbox("sweep_runs");
  sandbox.write("suite.json", suite(R"(["builtin:d1", "builtin:d2"])", "[1, 2]",
                                    R"(["is-graphs", "odometry"])", R"({"duration": 12})"));
  const auto first = sandbox.run("sweep suite.json -o out --jobs 2");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(countFiles(sandbox.dir() / "out", "metrics.json"), 8);
  EXPECT_TRUE(sandbox.exists("out/d2/odometry/seed-2/metrics.json"));
  EXPECT_THAT(first.err, HasSubstr("8/8 done, 0 running, 0 failed"));
  EXPECT_THAT(first.out, HasSubstr("8 of 8 cells finished, 0 failed, 0 not run"));
  const std::string csv = sandbox.read("out/table.csv");
  const auto table = sandbox.run("table out/d1/*/seed-* out/d2/*/seed-* --format csv");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_EQ(csv, table.out);
  EXPECT_THAT(csv, HasSubstr("is-graphs: runs"));

  const auto again = sandbox.run("sweep suite.json -o out --jobs 2");
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.err, HasSubstr("8 of 8 cells finished before; running the other 0"));
  EXPECT_EQ(sandbox.read("out/table.csv"), csv);

  // Another suite into the same folder is refused; --collect gives the same table.
  sandbox.write("other.json", suite(R"(["builtin:d2"])", "[1]", R"(["odometry"])", "{}"));
  const auto other = sandbox.run("sweep other.json -o out");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err,
              HasSubstr("out/sweep.json: this sweep folder holds another suite's cells"));
  const auto collected = sandbox.run("sweep --collect out");
  EXPECT_EQ(collected.exit_code, 0);
  EXPECT_EQ(sandbox.read("out/table.csv"), csv);
  // isg table given the sweep folder itself points to --collect.
  const auto folder = sandbox.run("table out");
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_EQ(folder.err,
            "isg table: error: out: a sweep folder, not a run folder: isg sweep --collect out "
            "tabulates it (or give its run folders, out/*/*/seed-*)\n");
}

TEST(Sweep, AFailedCellIsRecordedAndTheOthersGoOn) {
  testing::Sandbox sandbox("sweep_fail");
  // A plan file that exists (the suite is read) but that isg run refuses.
  sandbox.write("broken.json", R"({"format": "isg.plan", "version": 1})");
  sandbox.write("suite.json", suite(R"(["builtin:d2", "broken.json"])", "[1]", R"(["odometry"])",
                                    R"({"duration": 4})"));
  const auto r = sandbox.run("sweep suite.json -o out -q");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_TRUE(sandbox.exists("out/d2/odometry/seed-1/metrics.json"));
  EXPECT_FALSE(sandbox.exists("out/broken/odometry/seed-1"));
  const std::string record = sandbox.read("out/broken/odometry/seed-1.failed.json");
  EXPECT_THAT(record, HasSubstr("\"exit_code\": 1"));
  EXPECT_THAT(record, HasSubstr("broken.json: /levels: missing required field"));
  EXPECT_THAT(r.out, HasSubstr("failed: broken/odometry/seed-1: isg run: error: "));
  EXPECT_THAT(r.out, HasSubstr("1 of 2 cells finished, 1 failed, 0 not run"));
}

TEST(Sweep, BadSuitesNameTheFileAndThePlace) {
  testing::Sandbox sandbox("sweep_bad");
  sandbox.write("m.json", suite(R"(["builtin:d2"])", "[1]", R"(["is-graph"])", "{}"));
  const auto method = sandbox.run("sweep m.json -o out");
  EXPECT_EQ(method.exit_code, 1);
  EXPECT_THAT(method.err, HasSubstr("isg sweep: error: m.json: /methods/0: unknown method "
                                    "\"is-graph\" (one of is-graphs,"));
  EXPECT_FALSE(sandbox.exists("out"));
  sandbox.write("w.json", suite(R"(["plans/none.json"])", "[1]", R"(["odometry"])", "{}"));
  const auto world = sandbox.run("sweep w.json -o out");
  EXPECT_EQ(world.exit_code, 1);
  EXPECT_THAT(world.err, HasSubstr("w.json: /worlds/0: no such plan or scenario file: "));
  sandbox.write("b.json", suite(R"(["builtin:d7"])", "[1]", R"(["odometry"])", "{}"));
  EXPECT_THAT(sandbox.run("sweep b.json -o out").err,
              HasSubstr("b.json: /worlds/0: no built-in world \"d7\" (one of d1, d1.asbuilt,"));
  // A world's name is a folder name: control characters are refused (and sweep.json, which must
  // read back, never holds one).
  sandbox.write("c.json", suite(R"(["builtin:d1\u007f"])", "[1]", R"(["odometry"])", "{}"));
  EXPECT_THAT(sandbox.run("sweep c.json -o out").err,
              HasSubstr("c.json: /worlds/0: control character U+007F at byte 10"));
  // Nor may it be "..", which would put the run folders outside the sweep, or a file of the sweep.
  sandbox.write("...json", "{}");  // refused by its name before it is read
  sandbox.write("dots.json", suite(R"(["...json"])", "[1]", R"(["odometry"])", "{}"));
  EXPECT_THAT(sandbox.run("sweep dots.json -o out").err,
              HasSubstr("dots.json: /worlds/0: a world named \"..\" (its file's name without "
                        ".json) cannot name a folder of the sweep: rename the file"));
  sandbox.write("table.csv.json", "{}");
  sandbox.write("table.json", suite(R"(["table.csv.json"])", "[1]", R"(["odometry"])", "{}"));
  EXPECT_THAT(sandbox.run("sweep table.json -o out").err,
              HasSubstr("table.json: /worlds/0: a world named \"table.csv\" (its file's name "
                        "without .json) cannot name a folder of the sweep"));
  EXPECT_FALSE(sandbox.exists("out"));
  sandbox.write("g.json", suite(R"([{"generate": {"family": "hotel", "corridor_width": 0.3}}])",
                                "[1]", R"(["odometry"])", "{}"));
  const auto generated = sandbox.run("sweep g.json -o out");
  EXPECT_EQ(generated.exit_code, 1);
  EXPECT_THAT(generated.err, HasSubstr("g.json: /worlds/0/generate: corridor width: must be in"));
  // A sweep of more than a million cells is refused before anything is made.
  std::string seeds = "[1";
  for (int i = 2; i <= 51; ++i) seeds += ", " + std::to_string(i);
  sandbox.write("h.json", suite(R"([{"generate": {"family": "hall", "count": 10000}}])",
                                seeds + "]", R"(["odometry", "is-graphs"])", "{}"));
  EXPECT_THAT(sandbox.run("sweep h.json -o out").err,
              HasSubstr("h.json: 1020000 cells (10000 worlds × 2 methods × 51 seeds); a sweep "
                        "holds at most 1000000: split the suite"));
  // A method's options are checked when the suite is read, not cell by cell.
  sandbox.write("o.json", suite(R"(["builtin:d2"])", "[1]", R"(["amcl"])",
                                R"({"method_options": {"amcl": {"particle": 100}}})"));
  const auto option = sandbox.run("sweep o.json -o out");
  EXPECT_EQ(option.exit_code, 1);
  EXPECT_THAT(option.err, HasSubstr("isg sweep: error: o.json: /run/method_options/amcl: "
                                    "particle=100: amcl has no option particle (it has "));
  sandbox.write("n.json", suite(R"(["builtin:d2"])", "[1]", R"(["odometry"])",
                                R"({"method_options": {"dead-reckoning": {"particles": 1}}})"));
  EXPECT_THAT(sandbox.run("sweep n.json -o out").err,
              HasSubstr("/run/method_options/dead-reckoning: particles=1: odometry has no option "
                        "particles (it has none)"));
  sandbox.write("s.json", suite(R"(["builtin:d2"])", "[1, 1]", R"(["odometry"])", "{}"));
  EXPECT_THAT(sandbox.run("sweep s.json -o out").err, HasSubstr("/seeds/1: seed 1 twice"));
  EXPECT_EQ(sandbox.run("sweep s.json").exit_code, 2);  // no -o
  EXPECT_FALSE(sandbox.exists("out"));
  // -o naming a file: refused, the file left as it was.
  sandbox.write("d.json", suite(R"(["builtin:d2"])", "[1]", R"(["odometry"])", "{}"));
  sandbox.write("notes.txt", "mine\n");
  const auto file = sandbox.run("sweep d.json -o notes.txt");
  EXPECT_EQ(file.exit_code, 1);
  EXPECT_THAT(file.err, HasSubstr("isg sweep: error: notes.txt: exists and is not a folder; give "
                                  "a sweep folder"));
  EXPECT_EQ(sandbox.read("notes.txt"), "mine\n");
  EXPECT_THAT(sandbox.run("sweep --cell -1 out").err,
              HasSubstr("--cell: Value -1 not in range 0 to 999999"));
}

// Killed with SIGKILL midway (its running cells die with it), then started again: the sweep
// finishes the rest and its table is that of a sweep never interrupted.
TEST(Sweep, AKilledSweepStartedAgainFinishesWithIdenticalResults) {
  testing::Sandbox sandbox("sweep_kill");
  sandbox.write("suite.json", suite(R"(["builtin:d1"])", "[1, 2, 3]",
                                    R"(["is-graphs", "odometry"])", R"({"duration": 25})"));
  const fs::path dir = sandbox.dir();
  const std::string start = "cd '" + dir.string() + "' && ('" + std::string(ISG_EXECUTABLE) +
                            "' sweep suite.json -o killed -q > /dev/null 2>&1 & echo $! > pid)";
  ASSERT_EQ(std::system(start.c_str()), 0);
  // Wait for the first finished cell, then kill the sweep while the next one runs.
  for (int i = 0;
       i < 600 && (!fs::exists(dir / "killed") || countFiles(dir / "killed", "metrics.json") < 1);
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const int pid = std::stoi(sandbox.read("pid"));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const int finished = countFiles(dir / "killed", "metrics.json");
  EXPECT_GE(finished, 1);
  EXPECT_LT(finished, 6);  // it was killed midway
  const auto resumed = sandbox.run("sweep suite.json -o killed");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr(std::to_string(finished) + " of 6 cells finished before"));
  EXPECT_FALSE(anyPartial(dir / "killed"));
  ASSERT_EQ(sandbox.run("sweep suite.json -o clean -q").exit_code, 0);
  EXPECT_EQ(sandbox.read("killed/table.csv"), sandbox.read("clean/table.csv"));
}

TEST(Sweep, SlurmDryRunWritesAnArrayScript) {
  testing::Sandbox sandbox("sweep_slurm_script");
  sandbox.write("suite.json",
                R"({"format": "isg.suite", "version": 1, "name": "nightly",
                    "worlds": ["builtin:d1", {"generate": {"family": "hall", "seed": 4, "count": 2}}],
                    "seeds": [1, 2], "methods": ["odometry"],
                    "slurm": {"cpus_per_task": 2, "time": "00:20:00", "mem": "3G",
                              "partition": "short", "options": ["--qos=low"]}})");
  const auto r = sandbox.run("sweep suite.json -o out --backend slurm --dry-run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("sweep.sbatch (6 array tasks)"));
  const std::string script = sandbox.read("out/sweep.sbatch");
  for (const char* line :
       {"#SBATCH --job-name=isg-nightly\n", "#SBATCH --array=0-5\n", "#SBATCH --cpus-per-task=2\n",
        "#SBATCH --time=00:20:00\n", "#SBATCH --mem=3G\n", "#SBATCH --partition=short\n",
        "#SBATCH --qos=low\n", " sweep --cell \"$cell\" "}) {
    EXPECT_THAT(script, HasSubstr(line));
  }
  EXPECT_EQ(sandbox.read("out/slurm-cells.txt"), "0\n1\n2\n3\n4\n5\n");
  EXPECT_TRUE(sandbox.exists("out/worlds/hall-5.asbuilt.json"));
  // A task runs its cell as the local backend would.
  const auto task = sandbox.run("sweep --cell 5 out -q");
  EXPECT_EQ(task.exit_code, 0) << task.err;
  EXPECT_TRUE(sandbox.exists("out/hall-5/odometry/seed-2/metrics.json"));
  const auto collected = sandbox.run("sweep --collect out");
  EXPECT_EQ(collected.exit_code, 5);
  EXPECT_THAT(collected.out, HasSubstr("1 of 6 cells finished, 0 failed, 5 not run"));
  EXPECT_THAT(collected.out, HasSubstr("not run: d1/odometry/seed-1"));
  // Submitted again, only the cells left are in the array.
  ASSERT_EQ(sandbox.run("sweep suite.json -o out --backend slurm --dry-run").exit_code, 0);
  EXPECT_EQ(sandbox.read("out/slurm-cells.txt"), "0\n1\n2\n3\n4\n");
}

// sbatch reads #SBATCH lines as words, with quotes, backslash escapes and '#' comments, and the
// --output pattern reads '%': a suite name and a sweep folder holding them still arrive whole.
TEST(Sweep, SlurmScriptQuotesWhatSbatchWouldSplit) {
  testing::Sandbox sandbox("sweep_slurm_quotes");
  sandbox.write("suite.json",
                R"({"format": "isg.suite", "version": 1, "name": "nightly \"big\" run",
                    "worlds": ["builtin:d1"], "seeds": [1], "methods": ["odometry"],
                    "slurm": {"partition": "short"}})");
  const auto r = sandbox.run("sweep suite.json -o 'runs #2 (50%)' --backend slurm --dry-run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = sandbox.read("runs #2 (50%)/sweep.sbatch");
  EXPECT_THAT(script, HasSubstr("#SBATCH --job-name=\"isg-nightly \\\"big\\\" run\"\n"));
  EXPECT_THAT(script, HasSubstr("#SBATCH --partition=short\n"));
  EXPECT_THAT(script, HasSubstr("#SBATCH --output=\"" + sandbox.dir().string() +
                                "/runs #2 (50%%)/logs/slurm-%A_%a.out\"\n"));
}

// More cells than an array may hold: several arrays of one script, each told where its cells
// start in slurm-cells.txt.
TEST(Sweep, SlurmSplitsCellsBeyondTheArraySize) {
  testing::Sandbox sandbox("sweep_slurm_split");
  sandbox.write("suite.json",
                R"({"format": "isg.suite", "version": 1, "name": "split",
                    "worlds": ["builtin:d1", "builtin:d2", "builtin:d3"], "seeds": [1, 2, 3],
                    "methods": ["odometry"], "slurm": {"max_array_size": 4}})");
  const auto r = sandbox.run("sweep suite.json -o out --backend slurm --dry-run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = "out/sweep.sbatch";
  EXPECT_THAT(r.out, HasSubstr("(9 array tasks in 3 arrays of at most 4 tasks); submit it with:\n"
                               "  sbatch --array=0-3 '" +
                               script + "' 0\n  sbatch --array=0-3 '" + script +
                               "' 4\n  sbatch --array=0-0 '" + script + "' 8\n"));
  const std::string text = sandbox.read("out/sweep.sbatch");
  EXPECT_THAT(text, HasSubstr("#SBATCH --array=0-3\n"));
  EXPECT_THAT(text, HasSubstr("offset=${1:-0}\n"));
  EXPECT_THAT(text, HasSubstr("$((offset + SLURM_ARRAY_TASK_ID + 1))p"));
  // The script as Slurm would run task 1 of the second array: line 4 + 1 + 1 of the cells, cell 5.
  const std::string fake = "cd '" + sandbox.dir().string() +
                           "' && SLURM_ARRAY_TASK_ID=1 bash -c \"$(sed 's/^exec /echo /' "
                           "out/sweep.sbatch)\" task 4 > task.txt";
  ASSERT_EQ(std::system(fake.c_str()), 0);
  EXPECT_THAT(sandbox.read("task.txt"), HasSubstr(" sweep --cell 5 "));
}

}  // namespace
}  // namespace isg::cli
