#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "bim/plan_parser.hpp"
#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

// A binary PGM at 2 cm a pixel of a floor `width` × `height` metres with half a metre of light
// ground around it; `dark(x, y)` says which points (metres, from the floor's lower-left corner)
// are drawn dark. The image's lower-left corner is at (-0.5, -0.5) in the floor's frame.
template <class Dark>
std::string pgmOf(double width_m, double height_m, Dark dark) {
  const double resolution = 0.02, margin = 0.5;
  const int width = int((width_m + 2 * margin) / resolution),
            height = int((height_m + 2 * margin) / resolution);
  std::string bytes = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  for (int row = 0; row < height; ++row) {
    for (int c = 0; c < width; ++c) {
      const double x = (c + 0.5) * resolution - margin,
                   y = (height - row - 0.5) * resolution - margin;
      bytes += char(dark(x, y) ? 0 : 255);
    }
  }
  return bytes;
}

bool inBox(double x, double y, double x0, double y0, double x1, double y1) {
  return x >= x0 && x <= x1 && y >= y0 && y <= y1;
}

// The same floor as an 8-bit grey PNG (libpng's writer), its shades inverted when `negated`.
template <class Dark>
std::string pngOf(double width_m, double height_m, bool negated, Dark dark) {
  const std::string pgm = pgmOf(width_m, height_m, dark);
  // The PGM's header is "P5\nW H\n255\n": its raster is the last W × H bytes.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32((width_m + 1.0) / 0.02);
  image.height = png_uint_32((height_m + 1.0) / 0.02);
  image.format = PNG_FORMAT_GRAY;
  std::string raster = pgm.substr(pgm.size() - std::size_t(image.width) * image.height);
  if (negated) {
    for (char& v : raster) v = char(255 - static_cast<unsigned char>(v));
  }
  png_alloc_size_t size = 0;
  png_image_write_to_memory(&image, nullptr, &size, 0, raster.data(), 0, nullptr);
  std::string out(size, '\0');
  png_image_write_to_memory(&image, out.data(), &size, 0, raster.data(), 0, nullptr);
  out.resize(size);
  return out;
}

// A 4 m × 3 m room (wall axes) with 0.2 m walls and a 1 m doorway in its south wall.
std::string roomPgm() {
  return pgmOf(4.2, 3.2, [](double x, double y) {
    x -= 0.1, y -= 0.1;  // the walls' axes from (0, 0)
    const bool outer = inBox(x, y, -0.1, -0.1, 4.1, 3.1), room = inBox(x, y, 0.1, 0.1, 3.9, 2.9);
    const bool doorway = y < 0.2 && x > 1.5 && x < 2.5;
    return outer && !room && !doorway;
  });
}

TEST(RasterImport, APgmFloorPlanBecomesAPlanWithItsRoomAndDoorway) {
  testing::Sandbox sandbox("raster_import");
  sandbox.write("room.pgm", roomPgm());
  const auto result =
      sandbox.run("import room.pgm --resolution 0.02 --origin=-0.6,-0.6 -o room.json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("isg import: wrote room.json: 1 level, 4 walls, 0 columns, 1 doorway, "
                            "1 room; 0 regions left out or simplified"),
            std::string::npos)
      << result.err;
  const bim::Plan plan = bim::loadPlan((sandbox.dir() / "room.json").string());
  const auto& level = plan.levels.front();
  ASSERT_EQ(level.doors.size(), 1u);
  const bim::Wall* wall = level.findWall(level.doors[0].wall);
  ASSERT_NE(wall, nullptr);
  // The doorway's middle at (2, 0) in the plan (the image's corner placed at (-0.6, -0.6)).
  const Eigen::Vector2d d = (wall->end - wall->start).normalized();
  const Eigen::Vector2d middle = wall->start + level.doors[0].offset * d;
  EXPECT_NEAR(middle.x(), 2.0, 0.02);
  EXPECT_NEAR(middle.y(), 0.0, 0.02);
  EXPECT_NEAR(level.doors[0].width, 1.0, 0.04);
  EXPECT_EQ(sandbox.run("check room.json").exit_code, 0);
  // A second import over it needs --force, as for IFC.
  EXPECT_EQ(sandbox.run("import room.pgm --resolution 0.02 -o room.json").exit_code, 1);
  EXPECT_EQ(sandbox.run("import room.pgm --resolution 0.02 -o room.json --force").exit_code, 0);
}

TEST(RasterImport, AMapYamlBringsItsOwnScaleAndOrigin) {
  testing::Sandbox sandbox("raster_import_yaml");
  sandbox.write("room.pgm", roomPgm());
  sandbox.write("lab.yaml",
                "image: room.pgm\nresolution: 0.02\norigin: [-0.6, -0.6, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const auto result = sandbox.run("import lab.yaml -o lab.json -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const bim::Plan plan = bim::loadPlan((sandbox.dir() / "lab.json").string());
  ASSERT_EQ(plan.levels.front().rooms.size(), 1u);
  EXPECT_EQ(plan.name, "lab");
  const auto both = sandbox.run("import lab.yaml --resolution 0.05 -o other.json");
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_EQ(both.err,
            "isg import: error: lab.yaml: a map's YAML gives its own resolution and origin: leave "
            "out --resolution and --origin (or edit the YAML)\n");
  EXPECT_FALSE(sandbox.exists("other.json"));
}

TEST(RasterImport, AnImageWithoutItsScaleIsRefused) {
  testing::Sandbox sandbox("raster_import_scale");
  sandbox.write("room.pgm", roomPgm());
  const auto result = sandbox.run("import room.pgm -o room.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: room.pgm: a floor plan image needs its scale: --resolution M "
            "(metres a pixel; 0.01 for a plan drawn at 1 cm a pixel)\n");
  EXPECT_FALSE(sandbox.exists("room.json"));
  sandbox.write("blank.pgm", "P2 2 2 255\n255 255 255 255\n");
  const auto blank = sandbox.run("import blank.pgm --resolution 0.05 -o blank.json");
  EXPECT_EQ(blank.exit_code, 1);
  EXPECT_EQ(blank.err,
            "isg import: error: blank.pgm: no wall or column found in the image (0 dark regions): "
            "is it a floor plan with dark walls on a light ground (or is negate needed)?\n");
}

const auto kRoom = [](double x, double y) {
  x -= 0.1, y -= 0.1;
  const bool outer = inBox(x, y, -0.1, -0.1, 4.1, 3.1), room = inBox(x, y, 0.1, 0.1, 3.9, 2.9);
  return outer && !room && !(y < 0.2 && x > 1.5 && x < 2.5);
};

TEST(RasterImport, ANegatedMapWithAnOriginImportsToThePlanOfItsPng) {
  testing::Sandbox sandbox("raster_import_negate");
  sandbox.write("room.png", pngOf(4.2, 3.2, false, kRoom));
  sandbox.write("room_negated.png", pngOf(4.2, 3.2, true, kRoom));
  sandbox.write("lab.yaml",
                "image: room_negated.png\nresolution: 0.02\norigin: [3.5, -2.0, 0.0]\n"
                "negate: 1\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  ASSERT_EQ(sandbox.run("import room.png --resolution 0.02 --origin=3.5,-2 -o a.json").exit_code,
            0);
  ASSERT_EQ(sandbox.run("import lab.yaml -o b.json").exit_code, 0);
  const auto a = nlohmann::json::parse(sandbox.read("a.json"));
  const auto b = nlohmann::json::parse(sandbox.read("b.json"));
  EXPECT_EQ(a["levels"], b["levels"]);
  ASSERT_EQ(a["levels"][0]["walls"].size(), 4u);
  // The walls' south-west corner, drawn 0.6 m in from the image's corner both ways, lies 0.6 m
  // from the origin (3.5, -2).
  double min_x = 1e9, min_y = 1e9;
  for (const auto& wall : a["levels"][0]["walls"]) {
    for (const char* end : {"start", "end"}) {
      min_x = std::min(min_x, wall[end][0].get<double>());
      min_y = std::min(min_y, wall[end][1].get<double>());
    }
  }
  EXPECT_NEAR(min_x, 3.5 + 0.6, 0.02);
  EXPECT_NEAR(min_y, -2.0 + 0.6, 0.02);
}

// A map a robot made (formats/tests/data/nav2-maps: Nav2's TurtleBot3 sandbox, SLAM at 5 cm a
// pixel): its nine pillars, seen as rings around an unknown inside, are round columns on the
// world's 1.1 m grid, and the jagged arena around them one closed room.
TEST(RasterImport, ARealNav2MapImportsWithItsPillars) {
  testing::Sandbox sandbox("raster_import_nav2");
  const std::string map =
      std::string(ISG_SOURCE_DIR) + "/formats/tests/data/nav2-maps/tb3_sandbox.yaml";
  const auto result = sandbox.run("import '" + map + "' -o sandbox.json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const bim::Plan plan = bim::loadPlan((sandbox.dir() / "sandbox.json").string());
  const auto& level = plan.levels.front();
  int pillars = 0;
  for (const auto& column : level.columns) {
    if (!column.round()) continue;
    ++pillars;
    // The nearest grid point of {-1.1, 0, 1.1}², within the map's own 0.1 m.
    const Eigen::Vector2d grid(1.1 * std::round(column.center.x() / 1.1),
                               1.1 * std::round(column.center.y() / 1.1));
    EXPECT_LT((column.center - grid).norm(), 0.12) << column.id;
    EXPECT_NEAR(column.size.x(), 0.36, 0.05) << column.id;
  }
  EXPECT_EQ(pillars, 9);
  for (const auto& wall : level.walls) EXPECT_EQ(wall.name.find("column"), std::string::npos);
  EXPECT_EQ(level.rooms.size(), 1u);
  EXPECT_EQ(plan.imported_from->schema, "ROS map");
}

// An open floor: a 20 m × 12 m façade (0.3 m walls) with a 3 m gap in its east side, four
// 0.4 m columns and an L of partition, no room enclosed anywhere.
std::string openFloorPgm() {
  return pgmOf(20.3, 12.3, [](double x, double y) {
    x -= 0.15, y -= 0.15;  // the façade's axes from (0, 0)
    bool dark = inBox(x, y, -0.15, -0.15, 20.15, 0.15) || inBox(x, y, -0.15, 11.85, 20.15, 12.15) ||
                inBox(x, y, -0.15, -0.15, 0.15, 12.15) || inBox(x, y, 19.85, -0.15, 20.15, 4.5) ||
                inBox(x, y, 19.85, 7.5, 20.15, 12.15) || inBox(x, y, 11.0, 8.0, 16.0, 8.2) ||
                inBox(x, y, 15.8, 5.0, 16.0, 8.2);
    for (double cx : {5.0, 10.0}) {
      for (double cy : {4.0, 8.0})
        dark = dark || inBox(x, y, cx - 0.2, cy - 0.2, cx + 0.2, cy + 0.2);
    }
    return dark;
  });
}

TEST(RasterImport, AnOpenFloorIsImportedWalkedAndLocalizedOn) {
  testing::Sandbox sandbox("raster_open_floor");
  sandbox.write("site.pgm", openFloorPgm());
  const auto imported =
      sandbox.run("import site.pgm --resolution 0.02 --origin=-0.65,-0.65 -o site.json");
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_NE(imported.err.find("4 columns, 0 doorways, 0 rooms"), std::string::npos) << imported.err;
  const auto run = sandbox.run("run site.json --duration 90 --threads 2 -q -o runs/site");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto metrics = nlohmann::json::parse(sandbox.read("runs/site/metrics.json"));
  EXPECT_TRUE(metrics["localized"].get<bool>());
  EXPECT_LT(metrics["ape_B"]["rmse"].get<double>(), 0.05);
  EXPECT_GT(metrics["sim_seconds"].get<double>(), 60.0);
  EXPECT_EQ(metrics["time_wrongly_localized"].get<double>(), 0.0);
}

}  // namespace
}  // namespace isg::cli
