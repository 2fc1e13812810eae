// The module rule of docs/architecture.md holds for the whole tree, and the checker finds a bad
// include or link, naming file and line.
#include <gtest/gtest.h>

#include <fstream>

#include "architecture_rules.hpp"

namespace isg::architecture {
namespace {

// "(allowed: …)" as the checker writes it for a module.
std::string allowed(const std::string& module) {
  return "(allowed: " + join(allowedModules().at(module)) + ")";
}

TEST(Architecture, EveryIncludeAndLinkFollowsTheModuleRule) {
  const auto violations = check(ISG_SOURCE_DIR);
  std::string all;
  for (const auto& v : violations) all += v.str() + "\n";
  EXPECT_TRUE(violations.empty()) << all;
}

class ArchitectureChecker : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("isg_arch_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    for (const char* m : {"slam", "run", "sim", "worlds"}) fs::create_directories(root_ / m);
    write("slam/sgraph/sgraph.cpp",
          "#include \"slam/sgraph/sgraph.hpp\"\n#include \"bim/plane.hpp\"\n");
    write("run/driver.cpp", "#include \"slam/localizer.hpp\"\n#include \"common/tum.hpp\"\n");
    write("run/CMakeLists.txt",
          "add_library(isg_run driver.cpp)\ntarget_link_libraries(isg_run PUBLIC isg_slam\n"
          "  isg_eval PRIVATE ${PCL_LIBRARIES})\nisg_add_tests(run)\n");
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& file, const std::string& text) {
    fs::create_directories((root_ / file).parent_path());
    std::ofstream(root_ / file) << text;
  }
  std::vector<std::string> found() {
    std::vector<std::string> out;
    for (const auto& v : check(root_)) out.push_back(v.str());
    return out;
  }
  fs::path root_;
};

TEST_F(ArchitectureChecker, ACleanTreePasses) { EXPECT_TRUE(found().empty()); }

TEST_F(ArchitectureChecker, ABadIncludeIsNamedWithFileAndLine) {
  write("slam/bad.cpp", "#include <vector>\n\n#include \"sim/simulation.hpp\"\n");
  write("sim/loop.cpp",
        "#include \"sensors/messages.hpp\"\n#include \"slam/sgraph/sgraph.hpp\"\n"
        "#include \"slam/localizer.hpp\"\n");
  write("slam/baselines/amcl.cpp",
        "#include \"slam/localizer.hpp\"\n"
        "#include \"slam/isgraph/graph_matching.hpp\"\n");
  write("slam/sgraph/tests/t.cpp",
        "#include \"slam/sgraph/sgraph.hpp\"\n#include \"run/driver.hpp\"\n");
  write("run/x.hpp", "#include <mujoco/mujoco.h>\n#include <pcl/point_types.h>\n");
  write("slam/sgraph/y.cpp", "#include <zstd.h>\n#include <sensor_msgs/PointCloud2.h>\n");
  write("formats/z.cpp", "#include <zstd.h>\n#include <sensor_msgs/PointCloud2.h>\n");
  write("worlds/tests/t.cpp", "#include \"sim/mujoco_world.hpp\"\n");
  EXPECT_EQ(found(),
            (std::vector<std::string>{
                "run/x.hpp:1: run may not include MuJoCo (<mujoco/mujoco.h>): only sim "
                "runs it",
                "run/x.hpp:2: run may not include PCL (<pcl/point_types.h>) here: PCL "
                "stays inside slam's sources",
                "sim/loop.cpp:2: sim may not include \"slam/sgraph/sgraph.hpp\" " + allowed("sim"),
                "sim/loop.cpp:3: sim may not include \"slam/localizer.hpp\" " + allowed("sim"),
                "slam/bad.cpp:3: slam may not include \"sim/simulation.hpp\" " + allowed("slam"),
                "slam/baselines/amcl.cpp:2: slam/baselines may not include "
                "\"slam/isgraph/graph_matching.hpp\" " +
                    allowed("slam/baselines"),
                "slam/sgraph/tests/t.cpp:2: slam/sgraph may not include \"run/driver.hpp\" " +
                    allowed("slam/sgraph"),
                "slam/sgraph/y.cpp:1: slam/sgraph may not include <zstd.h>: file formats and "
                "their codecs stay inside formats",
                "slam/sgraph/y.cpp:2: slam/sgraph may not include <sensor_msgs/PointCloud2.h>: "
                "file formats and their codecs stay inside formats",
                "worlds/tests/t.cpp:1: worlds may not include \"sim/mujoco_world.hpp\" " +
                    allowed("worlds")}));
}

TEST_F(ArchitectureChecker, ABadLinkIsNamedWithFileAndLine) {
  write("run/CMakeLists.txt",
        "add_library(isg_run driver.cpp)\n\ntarget_link_libraries(isg_run PUBLIC isg_slam\n"
        "  isg_sim mujoco::mujoco)\n");
  write("worlds/CMakeLists.txt", "isg_add_tests(worlds isg_sim)\n");
  write("slam/sgraph/CMakeLists.txt",
        "add_library(isg_sgraph sgraph.cpp)\ntarget_link_libraries(isg_sgraph PUBLIC isg_slam "
        "isg_isgraph)\nisg_add_tests(sgraph isg_baselines)\n");
  EXPECT_EQ(found(),
            (std::vector<std::string>{
                "run/CMakeLists.txt:3: run may not link isg_sim " + allowed("run"),
                "run/CMakeLists.txt:3: run may not link mujoco::mujoco",
                "slam/sgraph/CMakeLists.txt:2: slam/sgraph may not link isg_isgraph " +
                    allowed("slam/sgraph"),
                "slam/sgraph/CMakeLists.txt:3: slam/sgraph may not link isg_baselines " +
                    allowed("slam/sgraph"),
                "worlds/CMakeLists.txt:1: worlds may not link isg_sim " + allowed("worlds")}));
}

}  // namespace
}  // namespace isg::architecture
