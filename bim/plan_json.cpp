#include "bim/plan_json.hpp"

#include "bim/plan_parser.hpp"

namespace isg::bim {

namespace {

using json = nlohmann::ordered_json;

json point(const Eigen::Vector2d& p) { return json::array({p.x(), p.y()}); }
json point(const Eigen::Vector3d& p) { return json::array({p.x(), p.y(), p.z()}); }

json wallJson(const Wall& w, const Level& level, const PlanJsonStyle& style) {
  json out = {
      {"id", w.id}, {"start", point(w.start)}, {"end", point(w.end)}, {"thickness", w.thickness}};
  if (style.every_wall_height || w.height != level.height) out["height"] = w.height;
  if (style.every_wall_height || w.base != 0.0) out["base"] = w.base;
  if (style.names && !w.name.empty()) out["name"] = w.name;
  if (!w.ifc_guid.empty()) out["ifc_guid"] = w.ifc_guid;
  return out;
}

json doorJson(const Door& d, const PlanJsonStyle& style) {
  json out = {{"id", d.id},
              {"wall", d.wall},
              {"offset", d.offset},
              {"width", d.width},
              {"height", d.height}};
  if (style.inferred_door_rooms || !d.rooms_inferred) out["rooms"] = {d.rooms[0], d.rooms[1]};
  if (style.names && !d.name.empty()) out["name"] = d.name;
  if (!d.ifc_guid.empty()) out["ifc_guid"] = d.ifc_guid;
  return out;
}

json windowJson(const Window& w, const PlanJsonStyle& style) {
  json out = {{"id", w.id},       {"wall", w.wall}, {"offset", w.offset},
              {"width", w.width}, {"sill", w.sill}, {"height", w.height}};
  if (style.names && !w.name.empty()) out["name"] = w.name;
  if (!w.ifc_guid.empty()) out["ifc_guid"] = w.ifc_guid;
  return out;
}

json roomJson(const Room& r) {
  json out = {{"id", r.id}};
  if (!r.name.empty()) out["name"] = r.name;
  json outline = json::array();
  for (const auto& p : r.outline) outline.push_back(point(p));
  out["outline"] = outline;
  if (!r.ifc_guid.empty()) out["ifc_guid"] = r.ifc_guid;
  return out;
}

json stairJson(const Stair& s, const PlanJsonStyle& style) {
  json out = {{"id", s.id}};
  if (style.names && !s.name.empty()) out["name"] = s.name;
  out["start"] = point(s.start);
  out["end"] = point(s.end);
  out["width"] = s.width;
  out["to"] = s.to;
  return out;
}

json columnJson(const Column& c, const Level& level, const PlanJsonStyle& style) {
  json out = {{"id", c.id}, {"center", point(c.center)}};
  if (c.round()) {
    out["diameter"] = c.size.x();
  } else {
    out["size"] = point(c.size);
    if (c.yaw != 0.0) out["yaw"] = c.yaw;
  }
  if (style.every_wall_height || c.height != level.height) out["height"] = c.height;
  if (style.every_wall_height || c.base != 0.0) out["base"] = c.base;
  if (style.names && !c.name.empty()) out["name"] = c.name;
  if (!c.ifc_guid.empty()) out["ifc_guid"] = c.ifc_guid;
  return out;
}

json levelJson(const Level& level, const PlanJsonStyle& style) {
  json out = {{"id", level.id}};
  if (style.names && !level.name.empty()) out["name"] = level.name;
  if (!level.ifc_guid.empty()) out["ifc_guid"] = level.ifc_guid;
  out["elevation"] = level.elevation;
  out["height"] = level.height;
  json walls = json::array(), doors = json::array();
  for (const auto& w : level.walls) walls.push_back(wallJson(w, level, style));
  for (const auto& d : level.doors) doors.push_back(doorJson(d, style));
  out["walls"] = walls;
  out["doors"] = doors;
  // Windows and stairs are optional extensions of v1: a level without them is written as before.
  if (!level.windows.empty()) {
    json windows = json::array();
    for (const auto& w : level.windows) windows.push_back(windowJson(w, style));
    out["windows"] = windows;
  }
  json rooms = json::array();
  for (const auto& r : level.rooms) rooms.push_back(roomJson(r));
  out["rooms"] = rooms;
  if (!level.stairs.empty()) {
    json stairs = json::array();
    for (const auto& s : level.stairs) stairs.push_back(stairJson(s, style));
    out["stairs"] = stairs;
  }
  if (!level.columns.empty()) {
    json columns = json::array();
    for (const auto& c : level.columns) columns.push_back(columnJson(c, level, style));
    out["columns"] = columns;
  }
  return out;
}

}  // namespace

json planToJson(const Plan& plan, const PlanJsonStyle& style) {
  json out = {{"format", kPlanFormat}, {"version", kPlanVersion}, {"name", plan.name}};
  if (style.names && plan.imported_from) {
    json from = json::object();
    if (!plan.imported_from->file.empty()) from["file"] = plan.imported_from->file;
    if (!plan.imported_from->schema.empty()) from["schema"] = plan.imported_from->schema;
    if (!plan.imported_from->application.empty())
      from["application"] = plan.imported_from->application;
    out["imported_from"] = from;
  }
  json levels = json::array();
  for (const auto& level : plan.levels) levels.push_back(levelJson(level, style));
  out["levels"] = levels;
  return out;
}

json asBuiltToJson(const AsBuilt& a, const AsBuiltJsonStyle& style) {
  json extra = json::array(), shifts = json::array(), clutter = json::array();
  for (const auto& w : a.extra_walls) {
    json wall = {{"start", point(w.start)}, {"end", point(w.end)}, {"thickness", w.thickness}};
    if (style.default_fields || w.base != 0.0) wall["base"] = w.base;
    if (style.default_fields || !w.level.empty()) wall["level"] = w.level;
    if (w.height) wall["height"] = *w.height;
    extra.push_back(wall);
  }
  for (const auto& s : a.wall_shifts) shifts.push_back({{"wall", s.wall}, {"offset", s.offset}});
  json rotations = json::array();
  for (const auto& r : a.wall_rotations) {
    json about = aboutName(r.about);
    if (r.about == WallRotation::About::kAlong) about = r.along_m;
    rotations.push_back({{"wall", r.wall}, {"angle_deg", r.angle_deg}, {"about", about}});
  }
  for (const auto& c : a.clutter) {
    json box = {
        {"shape", "box"}, {"center", point(c.center)}, {"size", point(c.size)}, {"yaw", c.yaw}};
    if (style.default_fields || !c.level.empty()) box["level"] = c.level;
    clutter.push_back(box);
  }
  json shortened = json::array();
  for (const auto& w : a.shortened_walls) {
    json built = json::array();
    for (const auto& [from, to] : w.built) built.push_back({from, to});
    shortened.push_back({{"wall", w.wall}, {"built", built}});
  }
  json moved = json::array();
  for (const auto& m : a.moved_columns) {
    moved.push_back({{"column", m.column}, {"offset", {m.offset.x(), m.offset.y()}}});
  }
  json out = json::object();
  const auto list = [&](const char* key, json value, bool always) {
    if (!value.empty() || (always && style.empty_lists)) out[key] = std::move(value);
  };
  list("missing_walls", a.missing_walls, true);
  list("extra_walls", std::move(extra), true);
  list("wall_shifts", std::move(shifts), true);
  // Turned and shortened walls came after the other deviations, columns as built later still:
  // written where there are some, so that a dataset without them records what it always did.
  list("wall_rotations", std::move(rotations), false);
  list("shortened_walls", std::move(shortened), false);
  list("closed_doors", a.closed_doors, true);
  list("clutter", std::move(clutter), true);
  list("missing_columns", a.missing_columns, false);
  list("moved_columns", std::move(moved), false);
  return out;
}

}  // namespace isg::bim
