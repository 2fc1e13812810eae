#include "bim/plan_json.hpp"

namespace isg::bim {

namespace {

using json = nlohmann::ordered_json;

json point(const Eigen::Vector2d& p) { return json::array({p.x(), p.y()}); }
json point(const Eigen::Vector3d& p) { return json::array({p.x(), p.y(), p.z()}); }

}  // namespace

json planToJson(const Plan& plan) {
  json levels = json::array();
  for (const auto& level : plan.levels) {
    json walls = json::array(), doors = json::array(), rooms = json::array();
    for (const auto& w : level.walls) {
      walls.push_back({{"id", w.id},
                       {"start", point(w.start)},
                       {"end", point(w.end)},
                       {"thickness", w.thickness},
                       {"height", w.height},
                       {"base", w.base}});
    }
    for (const auto& d : level.doors) {
      doors.push_back({{"id", d.id},
                       {"wall", d.wall},
                       {"offset", d.offset},
                       {"width", d.width},
                       {"height", d.height},
                       {"rooms", {d.rooms[0], d.rooms[1]}}});
    }
    for (const auto& r : level.rooms) {
      json outline = json::array();
      for (const auto& p : r.outline) outline.push_back(point(p));
      rooms.push_back({{"id", r.id}, {"name", r.name}, {"outline", outline}});
    }
    json out = {{"id", level.id},
                {"elevation", level.elevation},
                {"height", level.height},
                {"walls", walls},
                {"doors", doors}};
    // Windows are an optional extension of v1: a plan without them is written as before.
    if (!level.windows.empty()) {
      json windows = json::array();
      for (const auto& w : level.windows) {
        windows.push_back({{"id", w.id},
                           {"wall", w.wall},
                           {"offset", w.offset},
                           {"width", w.width},
                           {"sill", w.sill},
                           {"height", w.height}});
      }
      out["windows"] = windows;
    }
    out["rooms"] = rooms;
    // Stairs too are an optional extension of v1.
    if (!level.stairs.empty()) {
      json stairs = json::array();
      for (const auto& st : level.stairs) {
        stairs.push_back({{"id", st.id},
                          {"start", point(st.start)},
                          {"end", point(st.end)},
                          {"width", st.width},
                          {"to", st.to}});
      }
      out["stairs"] = stairs;
    }
    levels.push_back(out);
  }
  return {{"format", "isg.plan"}, {"version", 1}, {"name", plan.name}, {"levels", levels}};
}

json asBuiltToJson(const AsBuilt& a) {
  json extra = json::array(), shifts = json::array(), clutter = json::array();
  for (const auto& w : a.extra_walls) {
    json wall = {{"start", point(w.start)},
                 {"end", point(w.end)},
                 {"thickness", w.thickness},
                 {"base", w.base},
                 {"level", w.level}};
    if (w.height) wall["height"] = *w.height;
    extra.push_back(wall);
  }
  for (const auto& s : a.wall_shifts) shifts.push_back({{"wall", s.wall}, {"offset", s.offset}});
  for (const auto& c : a.clutter) {
    clutter.push_back({{"shape", "box"},
                       {"center", point(c.center)},
                       {"size", point(c.size)},
                       {"yaw", c.yaw},
                       {"level", c.level}});
  }
  return {{"missing_walls", a.missing_walls},
          {"extra_walls", extra},
          {"wall_shifts", shifts},
          {"closed_doors", a.closed_doors},
          {"clutter", clutter}};
}

}  // namespace isg::bim
