#include "bim/agraph_json.hpp"

namespace isg::bim {

namespace {

// Ordered, so that the file reads top-down: format, plan, nodes, edges.
using json = nlohmann::ordered_json;

// Six decimals: micrometres, enough for any plan and short enough to read.
double rounded(double v) {
  const double r = std::round(v * 1e6) / 1e6;
  return r == 0.0 ? 0.0 : r;  // no -0
}

json vec(const Eigen::Vector2d& v) { return json::array({rounded(v.x()), rounded(v.y())}); }
json vec(const Eigen::Vector3d& v) {
  return json::array({rounded(v.x()), rounded(v.y()), rounded(v.z())});
}

json edge(const char* type, const std::string& from, const std::string& to) {
  return {{"type", type}, {"from", from}, {"to", to}};
}

}  // namespace

nlohmann::ordered_json agraphToJson(const AGraph& g) {
  json surfaces = json::array(), walls = json::array(), rooms = json::array(),
       doorways = json::array(), floors = json::array(), edges = json::array();
  for (const auto& s : g.surfaces) {
    json segments = json::array();
    for (const auto& [a, b] : s.segments) segments.push_back({vec(a), vec(b)});
    surfaces.push_back({{"id", s.id},
                        {s.stair.empty() ? "wall" : "stair", s.stair.empty() ? s.wall : s.stair},
                        {"level", s.level},
                        {"side", s.side > 0 ? "left" : "right"},
                        {"axis", toString(s.axis)},
                        {"plane", {{"n", vec(s.plane.normal)}, {"d", rounded(s.plane.d)}}},
                        {"closest_point", vec(s.plane.closestPoint())},
                        {"segments", segments},
                        {"z", {rounded(s.z_min), rounded(s.z_max)}}});
  }
  for (const auto& w : g.walls) {
    const std::string& left = g.surfaces[w.left_surface].id;
    const std::string& right = g.surfaces[w.right_surface].id;
    walls.push_back({{"id", w.id},
                     {"level", w.level},
                     {"surfaces", {left, right}},
                     {"anchor", vec(w.anchor)},
                     {"centre", vec(w.centre)},
                     {"thickness", rounded(w.thickness)},
                     {"length", rounded(w.length)}});
    edges.push_back(edge("wall_surface", w.id, left));
    edges.push_back(edge("wall_surface", w.id, right));
  }
  for (const auto& r : g.rooms) {
    json surface_ids = json::array();
    for (int s : r.surfaces) surface_ids.push_back(s >= 0 ? json(g.surfaces[s].id) : json(nullptr));
    json pairs = json::array();
    for (const auto& p : r.pairs) pairs.push_back({g.surfaces[p[0]].id, g.surfaces[p[1]].id});
    json outline = json::array();
    for (const auto& p : r.outline) outline.push_back(vec(p));
    json widths = json::array();
    for (double w : r.widths) widths.push_back(rounded(w));
    json room = {{"id", r.id},
                 {"name", r.name},
                 {"level", r.level},
                 {"kind", toString(r.kind)},
                 {"centre", vec(r.centre)},
                 {"surfaces", surface_ids},
                 {"pairs", pairs},
                 {"widths", widths},
                 {"outline", outline}};
    if (r.kind == RoomKind::kTwoWall) room["axis_point"] = vec(r.axis_point);
    rooms.push_back(room);
    for (int s : r.surfaces) {
      if (s >= 0) edges.push_back(edge("room_surface", r.id, g.surfaces[s].id));
    }
  }
  for (const auto& d : g.doorways) {
    json joined = json::array();
    for (int r : d.rooms) {
      joined.push_back(g.rooms[r].id);
      edges.push_back(edge("doorway_room", d.id, g.rooms[r].id));
    }
    doorways.push_back({{"id", d.id},
                        {"wall", d.wall},
                        {"level", d.level},
                        {"position", vec(d.position)},
                        {"width", rounded(d.width)},
                        {"rooms", joined},
                        {"outside", d.rooms.size() < 2}});
  }
  for (const auto& f : g.floors) {
    json ids = json::array();
    for (int r : f.rooms) {
      ids.push_back(g.rooms[r].id);
      edges.push_back(edge("floor_room", f.id, g.rooms[r].id));
    }
    floors.push_back({{"id", f.id},
                      {"elevation", rounded(f.elevation)},
                      {"centre", vec(f.centre)},
                      {"rooms", ids}});
  }
  return {{"format", "isg.agraph"},
          {"version", 1},
          {"plan", g.plan_name},
          {"frame", "B"},
          {"nodes",
           {{"wall_surfaces", surfaces},
            {"walls", walls},
            {"rooms", rooms},
            {"doorways", doorways},
            {"floors", floors}}},
          {"edges", edges}};
}

namespace {

std::string itemsPerLine(const json& array, const std::string& indent) {
  if (array.empty()) return "[]";
  std::string out = "[\n";
  for (std::size_t i = 0; i < array.size(); ++i) {
    out += indent + "  " + array[i].dump() + (i + 1 < array.size() ? ",\n" : "\n");
  }
  return out + indent + "]";
}

}  // namespace

std::string agraphJsonText(const json& document) {
  std::string out = "{\n";
  std::size_t k = 0;
  for (const auto& [key, value] : document.items()) {
    out += "  " + json(key).dump() + ": ";
    if (key == "nodes") {
      out += "{\n";
      std::size_t j = 0;
      for (const auto& [kind, nodes] : value.items()) {
        out += "    " + json(kind).dump() + ": " + itemsPerLine(nodes, "    ");
        out += (++j < value.size() ? ",\n" : "\n");
      }
      out += "  }";
    } else if (value.is_array()) {
      out += itemsPerLine(value, "  ");
    } else {
      out += value.dump();
    }
    out += (++k < document.size() ? ",\n" : "\n");
  }
  return out + "}\n";
}

}  // namespace isg::bim
