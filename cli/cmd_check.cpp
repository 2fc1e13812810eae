#include "cli/cmd_check.hpp"

#include <cstdio>
#include <iostream>
#include <string>

#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"
#include "common/plural.hpp"

namespace isg::cli {

CheckCommand::CheckCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("check", "Validate a plan or scenario and describe it");
  app_->footer(
      "Checks every rule of the isg.plan and isg.scenario formats. On the first violation it "
      "prints the file, the JSON pointer and what is wrong, and exits with 1. Warnings (unknown "
      "fields, clockwise outlines, doors whose rooms cannot be inferred) do not fail the "
      "check.\n\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN|SCENARIO")
      ->required();
  app_->add_flag("-v,--verbose", verbose_,
                 "also list every room with its bounding wall faces and every door with its rooms");
}

int CheckCommand::run() {
  const bim::Scenario scenario = loadInput(input_, "check");
  const bim::Plan& plan = scenario.plan;
  std::size_t walls = 0, doors = 0, windows = 0, rooms = 0, stairs = 0, columns = 0, round = 0;
  for (const auto& level : plan.levels) {
    walls += level.walls.size();
    doors += level.doors.size();
    windows += level.windows.size();
    rooms += level.rooms.size();
    stairs += level.stairs.size();
    columns += level.columns.size();
    for (const auto& c : level.columns) round += c.round();
  }
  // Windows are an optional extension: a plan without them is summarised as before.
  const std::string window_count =
      windows > 0 ? ", " + std::to_string(windows) + " window" + (windows == 1 ? "" : "s") : "";
  // So are stairs.
  const std::string stair_count =
      stairs > 0
          ? ", " + std::to_string(stairs) + (stairs == 1 ? " flight" : " flights") + " of stairs"
          : "";
  // And columns.
  const std::string column_count =
      columns == 0 ? ""
                   : ", " + common::counted(columns, "column") +
                         (round > 0 ? " (" + std::to_string(round) + " round)" : "");
  std::printf("%s: ok: plan \"%s\" (%s): %s, %s%s, %s%s, %s%s\n", input_.c_str(), plan.name.c_str(),
              scenario.plan_file.c_str(), common::counted(plan.levels.size(), "level").c_str(),
              common::counted(walls, "wall").c_str(), column_count.c_str(),
              common::counted(doors, "door").c_str(), window_count.c_str(),
              common::counted(rooms, "room").c_str(), stair_count.c_str());
  const auto& ab = scenario.as_built;
  if (!ab.empty()) {
    // Turned walls are named only when there are some: the line stays as it was for the rest.
    const std::string turned = ab.wall_rotations.empty()
                                   ? ""
                                   : std::to_string(ab.wall_rotations.size()) + " turned walls, ";
    const std::string shortened =
        ab.shortened_walls.empty()
            ? ""
            : std::to_string(ab.shortened_walls.size()) + " walls built in part, ";
    const std::string columns =
        ab.missing_columns.empty() && ab.moved_columns.empty()
            ? ""
            : ", " + std::to_string(ab.missing_columns.size()) + " missing columns, " +
                  std::to_string(ab.moved_columns.size()) + " moved columns";
    std::printf(
        "  as built: %zu missing walls, %zu extra walls, %zu shifted walls, %s%s"
        "%zu closed doors, %zu clutter boxes%s\n",
        ab.missing_walls.size(), ab.extra_walls.size(), ab.wall_shifts.size(), turned.c_str(),
        shortened.c_str(), ab.closed_doors.size(), ab.clutter.size(), columns.c_str());
  }
  if (!verbose_) return kExitOk;
  for (const auto& level : plan.levels) {
    const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
    std::printf("  level %s: elevation %.3f m, height %.3f m\n", level.id.c_str(), level.elevation,
                level.height);
    for (const auto& room : level.rooms) {
      std::printf("    room %-6s %-28s %zu sides, %.2f m², bounded by:", room.id.c_str(),
                  ("\"" + room.name + "\"").c_str(), room.outline.size(),
                  bim::signedArea(room.outline));
      for (const auto& b : geometry.boundariesOf(room.id)) {
        std::printf(" %s.%s(edge %d)", b.wall.c_str(), b.side > 0 ? "left" : "right", b.edge);
      }
      std::printf("\n");
    }
    for (const auto& door : level.doors) {
      std::printf("    door %-6s in %-6s joins %s and %s%s\n", door.id.c_str(), door.wall.c_str(),
                  door.rooms[0].c_str(), door.rooms[1].c_str(),
                  door.rooms_inferred ? " (inferred)" : "");
    }
  }
  return kExitOk;
}

}  // namespace isg::cli
