#include "ifc/ifc_importer.hpp"

#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcColumn.h>
#include <ifcpp/IFC4/include/IfcCurtainWall.h>
#include <ifcpp/IFC4/include/IfcDoor.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcMaterialLayer.h>
#include <ifcpp/IFC4/include/IfcMaterialLayerSet.h>
#include <ifcpp/IFC4/include/IfcMaterialLayerSetUsage.h>
#include <ifcpp/IFC4/include/IfcNonNegativeLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcOpeningElement.h>
#include <ifcpp/IFC4/include/IfcOpeningElementTypeEnum.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelAssociatesMaterial.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/IFC4/include/IfcRelFillsElement.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcSpace.h>
#include <ifcpp/IFC4/include/IfcStair.h>
#include <ifcpp/IFC4/include/IfcStairFlight.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/IFC4/include/IfcWindow.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>

#include "bim/free_space_rooms.hpp"
#include "bim/limits.hpp"
#include "bim/plan.hpp"
#include "bim/plan_json.hpp"
#include "bim/plan_parser.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "common/plural.hpp"
#include "ifc/ifcpp_model.hpp"

namespace isg::ifc::importer {

// The element's GlobalId as the plan keeps it (`ifc_guid`): "" unless it is one as IFC writes
// them (a damaged file's may be anything).
static std::string keptGlobalId(const std::string& global_id) {
  return bim::isIfcGlobalId(global_id) ? global_id : "";
}

void Importer::levelColumns(int s, StoreySummary& summary, bim::Level& level) {
  const double e = storeys_[s].elevation;
  for (const ColumnRecord& record : columns_) {
    if (!standsOn(record.fit, e)) continue;
    bim::Column column;
    column.id = uniqueId(record.global_id, summary.level_id);
    column.shape = record.round ? bim::Column::Shape::kRound : bim::Column::Shape::kRectangle;
    column.center = record.center;
    column.size = record.size;
    column.yaw = record.yaw;
    column.base = std::max(0.0, record.fit.bottom - e);
    column.height = std::min(record.fit.top - e, bim::limits::kMaxHeight);
    if (!record.name.empty()) column.name = cleanText(record.name, common::limits::kMaxTextBytes);
    column.ifc_guid = keptGlobalId(record.global_id);
    level.columns.push_back(std::move(column));
    ++summary.columns;
  }
}

// Each flight joins the imported level whose floor is at its bottom to the one whose floor is at
// its top (within kFlightLevelTolerance: a flight's last tread may be the upper slab's edge, one
// riser higher). Flights that do not (to or from a landing between storeys) are dropped; the
// plan's parser checks the rest (slope, width, clear of walls) when the plan is read back.
FlightFit Importer::clearOfWalls(const FlightRecord& flight, const bim::Level& lower,
                                 const bim::Level& upper) {
  FlightFit fit = flight.fit;
  const Eigen::Vector2d origin = fit.low_edge;
  const Eigen::Vector2d u = (fit.high_edge - fit.low_edge).normalized();
  const Eigen::Vector2d n(-u.y(), u.x());
  // The flight in its own frame: s along it from the low edge, t across it.
  double s0 = 0.0, s1 = (fit.high_edge - fit.low_edge).norm();
  double t0 = -0.5 * fit.width, t1 = 0.5 * fit.width;
  for (const bim::Level* level : {&lower, &upper}) {
    for (const bim::Wall& wall : level->walls) {
      const auto corners = bim::wallRectangle(wall);
      double ws0 = 1e300, ws1 = -1e300, wt0 = 1e300, wt1 = -1e300;
      for (const auto& c : corners) {
        ws0 = std::min(ws0, (c - origin).dot(u)), ws1 = std::max(ws1, (c - origin).dot(u));
        wt0 = std::min(wt0, (c - origin).dot(n)), wt1 = std::max(wt1, (c - origin).dot(n));
      }
      const std::vector<Eigen::Vector2d> rectangle{
          origin + s0 * u + t0 * n, origin + s1 * u + t0 * n, origin + s1 * u + t1 * n,
          origin + s0 * u + t1 * n};
      if (!bim::convexPolygonsOverlap(rectangle, corners, 1e-3)) continue;
      // The smallest trim of one end or one side that clears the wall, if small enough.
      struct Trim {
        double amount;
        double* edge;
        double to;
        const char* where;
      };
      const Trim trims[] = {{ws1 - s0, &s0, ws1, "its bottom end"},
                            {s1 - ws0, &s1, ws0, "its top end"},
                            {wt1 - t0, &t0, wt1, "its right side"},
                            {t1 - wt0, &t1, wt0, "its left side"}};
      const Trim* best = nullptr;
      for (const Trim& trim : trims) {
        if (trim.amount > 0 && (!best || trim.amount < best->amount)) best = &trim;
      }
      if (best == nullptr || best->amount > kFlightTrim) continue;  // the parser will say why
      *best->edge = best->to;
      simplified(describe(flight.kind, flight.element),
                 std::string(best->where) + " trimmed by " + fmt(best->amount) +
                     " m to clear wall " + wall.id +
                     " (a flight's stringer or last tread built into a wall)");
    }
  }
  fit.low_edge = origin + s0 * u + 0.5 * (t0 + t1) * n;
  fit.high_edge = origin + s1 * u + 0.5 * (t0 + t1) * n;
  fit.width = t1 - t0;
  return fit;
}

void Importer::placeFlights(std::vector<bim::Level>& levels) {
  for (const auto& flight : flights_) {
    const std::string what = describe(flight.kind, flight.element);
    bim::Level* lower = nullptr;
    bim::Level* upper = nullptr;
    for (auto& level : levels) {
      if (std::abs(level.elevation - flight.fit.bottom) <= kFlightLevelTolerance) lower = &level;
      if (std::abs(level.elevation - flight.fit.top) <= kFlightLevelTolerance) upper = &level;
    }
    if (lower == nullptr || upper == nullptr || lower == upper) {
      dropped(what, "it rises from z " + fmt(flight.fit.bottom) + " to " + fmt(flight.fit.top) +
                        " m, not from one imported level's floor to another's (within " +
                        fmt(kFlightLevelTolerance) +
                        " m): entrance steps, or a flight to or from a half landing; the plan "
                        "holds straight flights between two levels only");
      continue;
    }
    const FlightFit fit = clearOfWalls(flight, *lower, *upper);
    const double run = (fit.high_edge - fit.low_edge).norm();
    bim::Stair stair;
    stair.id = uniqueId(flight.global_id, "");
    stair.name = cleanText(flight.name, common::limits::kMaxTextBytes);
    stair.start = fit.low_edge;
    stair.end = fit.high_edge;
    stair.width = fit.width;
    stair.to = upper->id;
    const double rise = upper->elevation - lower->elevation;
    if (std::abs(flight.fit.top - flight.fit.bottom - rise) > kReportedChange) {
      simplified(what, "its body rises " + fmt(flight.fit.top - flight.fit.bottom) +
                           " m; taken as a flight of " + fmt(run) + " m from level " + lower->id +
                           " to level " + upper->id + ", " + fmt(rise) + " m up");
    }
    lower->stairs.push_back(std::move(stair));
  }
}

std::vector<int> Importer::chooseLevels() {
  std::vector<int> chosen;
  std::vector<int> walls_on(storeys_.size(), 0), own_walls_on(storeys_.size(), 0);
  for (int s = 0; s < int(storeys_.size()); ++s) {
    for (const auto& wall : walls_) {
      const bool on = standsOn(wall.fit, storeys_[s].elevation) &&
                      wall.fit.top >= storeys_[s].elevation + kFullHeightWall;
      walls_on[s] += on;
      own_walls_on[s] += on && wall.storey == s;
    }
  }
  if (!options_.storeys.empty()) {
    for (const auto& name : options_.storeys) {
      int found = -1;
      for (int s = 0; s < int(storeys_.size()); ++s) {
        if (storeys_[s].name == name) found = s;
      }
      if (found < 0) {
        std::string names;
        for (const auto& s : storeys_)
          names += (names.empty() ? "" : ", ") + ("\"" + s.name + "\"");
        throw common::InputError(
            file_, "", "no storey named \"" + name + "\" (--storey); its storeys: " + names);
      }
      if (walls_on[found] == 0) {
        throw common::InputError(file_, "",
                                 "storey \"" + name + "\" has no wall rising " +
                                     fmt(kFullHeightWall) +
                                     " m above its floor: nothing to import");
      }
      if (std::find(chosen.begin(), chosen.end(), found) == chosen.end()) chosen.push_back(found);
    }
    std::sort(chosen.begin(), chosen.end());
    return chosen;
  }
  // Every storey with walls standing on it, spaces or not: a storey without IfcSpace (a building
  // under construction, an upper storey modelled without them) gets its rooms from the free
  // space its walls enclose (levelRooms).
  // A storey without spaces whose standing walls are all another storey's (a roof or
  // reference storey a few centimetres off a floor) would repeat that floor: left out, said.
  for (int s = 0; s < int(storeys_.size()); ++s) {
    if (walls_on[s] > 0 && (!storeys_[s].spaces.empty() || own_walls_on[s] > 0)) {
      chosen.push_back(s);
    }
  }
  if (chosen.empty()) {
    // Nothing is written, so the summary that lists what was left out never prints: the reasons
    // go into the error itself, with what IFC++ said while reading.
    std::string why = walls_.empty() ? "no wall the import could read: nothing to import"
                                     : "no storey has walls standing on it: nothing to import";
    constexpr std::size_t kListed = 5;
    const auto& log = result_.log;
    if (!log.empty()) {
      why += " (" + common::counted(log.size(), "element") + " left out or simplified: ";
      for (std::size_t i = 0; i < std::min(log.size(), kListed); ++i) {
        why += (i > 0 ? "; " : "") + log[i];
      }
      why +=
          log.size() > kListed ? "; and " + std::to_string(log.size() - kListed) + " more)" : ")";
    }
    const auto& errors = loaded_.messages.errors;
    if (!errors.empty()) {
      why += "; IFC++ reported " + common::counted(errors.size(), "error") +
             " while reading (first: " + errors.front() + ")";
    }
    throw common::InputError(file_, "", why);
  }
  return chosen;
}

std::map<int, std::pair<double, double>> Importer::levelWalls(int s, StoreySummary& summary,
                                                              bim::Level& level) {
  const double e = storeys_[s].elevation;
  std::map<int, std::pair<double, double>> base_top;  // wall → (base, top) above the level
  for (int w = 0; w < int(walls_.size()); ++w) {
    const WallRecord& wall = walls_[w];
    if (!standsOn(wall.fit, e)) continue;
    const std::string id = uniqueId(wall.global_id, summary.level_id);
    wall_ids_[{w, s}] = id;
    const double base = std::max(0.0, wall.fit.bottom - e);
    const double top = std::min(wall.fit.top - e, bim::limits::kMaxHeight);
    base_top[w] = {base, top};
    bim::Wall out;
    out.id = id;
    out.start = wall.fit.start;
    out.end = wall.fit.end;
    out.thickness = wall.fit.thickness;
    out.height = top;
    out.base = base;
    if (!wall.name.empty()) out.name = cleanText(wall.name, common::limits::kMaxTextBytes);
    out.ifc_guid = keptGlobalId(wall.global_id);
    level.walls.push_back(std::move(out));
    ++summary.walls;
    if (wall.storey != s) ++summary.walls_from_other_storeys;
  }
  return base_top;
}

int Importer::homeOf(const OpeningRecord& opening) const {
  // The highest floor at or below the opening's bottom among the levels its wall stands on.
  const WallRecord& wall = walls_[opening.wall];
  int home = -1;
  for (int t = 0; t < int(storeys_.size()); ++t) {
    if (is_level_[t] && standsOn(wall.fit, storeys_[t].elevation) &&
        storeys_[t].elevation <= opening.extent.z_min + kStandingHeight &&
        (home < 0 || storeys_[t].elevation > storeys_[home].elevation)) {
      home = t;
    }
  }
  return home;
}

bool Importer::doorOf(const OpeningRecord& opening, const std::string& what, double above_base,
                      double head_room, bim::Door& door) {
  if (head_room < 0.5) {
    dropped(what, "its head is " + fmt(head_room) + " m above the floor: not a door");
    return false;
  }
  if (above_base > kFloorTolerance) {
    simplified(what, "its opening starts " + fmt(above_base) +
                         " m above the floor: the door is taken from the floor");
  }
  if (opening.kind == "opening") simplified(what, "an opening without a door or window: a doorway");
  door.height = head_room;
  return true;
}

bool Importer::windowOf(const OpeningRecord& opening, const std::string& what, double above_base,
                        double head, double wall_height, bim::Window& window) {
  const double sill = std::max(0.0, above_base);
  const double cut_head = std::min(head, wall_height);
  if (cut_head - sill < 0.05) {
    dropped(what, "no height left inside its wall");
    return false;
  }
  if (head > wall_height + 0.01)
    simplified(what, "its head is above its wall's top: cut at the top");
  if (opening.kind == "opening")
    simplified(what, "an opening without a door or window, above the floor: a window");
  window.sill = sill;
  window.height = cut_head - sill;
  return true;
}

void Importer::placeOpening(const OpeningRecord& opening, int s,
                            const std::pair<double, double>& base_top,
                            std::vector<PlacedOpening>& along_wall, StoreySummary& summary,
                            bim::Level& level) {
  const WallRecord& wall = walls_[opening.wall];
  const double e = storeys_[s].elevation;
  const std::string what =
      describe(opening.kind, opening.described) + " (in wall " + wall.global_id + ")";
  const double length = (wall.fit.end - wall.fit.start).norm();
  const double lo = std::max(0.0, opening.extent.along_min);
  const double hi = std::min(length, opening.extent.along_max);
  if (hi - lo < kMinOpeningWidth) {
    dropped(what, "narrower than " + fmt(kMinOpeningWidth) + " m within its wall");
    return;
  }
  if (hi - lo < opening.extent.along_max - opening.extent.along_min - 0.01) {
    simplified(what,
               "it reaches beyond its wall's end: cut to the wall, " + fmt(hi - lo) + " m wide");
  }
  const auto [base, top] = base_top;
  const double above_base = opening.extent.z_min - (e + base);
  bool is_door = opening.kind == "door";
  if (opening.kind == "opening") {
    is_door = above_base < kFloorTolerance &&
              opening.extent.z_max - opening.extent.z_min >= kMinDoorwayHeight;
  }
  for (const auto& other : along_wall) {
    if (lo < other.hi - 1e-6 && other.lo < hi - 1e-6) {
      dropped(what, "overlaps " + other.kind + " " + other.id + " along the wall");
      return;
    }
  }
  const std::string id = uniqueId(opening.global_id, summary.level_id);
  bim::Door door;
  bim::Window window;
  door.id = window.id = id;
  door.wall = window.wall = wall_ids_[{opening.wall, s}];
  door.offset = window.offset = 0.5 * (lo + hi);
  door.width = window.width = hi - lo;
  door.rooms_inferred = true;  // the model says none: the parser finds them from the outlines
  const double head = opening.extent.z_max - (e + base);  // above the wall's base
  if (is_door ? !doorOf(opening, what, above_base, std::min(head, top - base), door)
              : !windowOf(opening, what, above_base, head, top - base, window)) {
    return;
  }
  ++(is_door ? summary.doors : summary.windows);
  if (!opening.name.empty()) {
    door.name = window.name = cleanText(opening.name, common::limits::kMaxTextBytes);
  }
  door.ifc_guid = window.ifc_guid = keptGlobalId(opening.global_id);
  if (is_door) {
    level.doors.push_back(std::move(door));
  } else {
    level.windows.push_back(std::move(window));
  }
  along_wall.push_back({lo, hi, id, is_door ? "door" : "window"});
}

void Importer::levelRooms(const StoreyRecord& storey, StoreySummary& summary, bim::Level& level) {
  if (storey.spaces.empty()) {
    freeSpaceRooms(storey, summary, level);
    return;
  }
  for (const auto& [space, footprint] : storey.spaces) {
    const std::string what = describe("space", space);
    if (!footprint || footprint->outline.size() < 3 ||
        std::abs(bim::signedArea(footprint->outline)) < 0.01) {
      dropped(what, "no closed outline at the bottom of its body");
      continue;
    }
    if (footprint->outline.size() > 10000) {
      dropped(what, "its outline has more than 10 000 vertices");
      continue;
    }
    if (bim::findSelfIntersection(footprint->outline)) {
      dropped(what, "its outline crosses itself");
      continue;
    }
    if (footprint->loops > 1) {
      simplified(
          what,
          std::to_string(footprint->loops - 1) +
              " hole(s) in its outline (columns, shafts) left out: the room is its outer outline");
    }
    const std::string long_name = labelText(space->m_LongName);
    const std::string short_name = labelText(space->m_Name);
    std::string name = short_name;
    if (!long_name.empty() && long_name != short_name)
      name += (name.empty() ? "" : " ") + long_name;
    bim::Room room;
    room.id = uniqueId(globalIdOf(space), summary.level_id);
    if (!name.empty()) room.name = cleanText(name, common::limits::kMaxTextBytes);
    room.outline = footprint->outline;
    room.ifc_guid = keptGlobalId(globalIdOf(space));
    level.rooms.push_back(std::move(room));
    ++summary.rooms;
  }
}

void Importer::freeSpaceRooms(const StoreyRecord& storey, StoreySummary& summary,
                              bim::Level& level) {
  const bim::FreeSpaceRooms found = bim::enclosedFreeSpaces(level);
  for (std::size_t k = 0; k < found.outlines.size(); ++k) {
    bim::Room room;
    room.id = uniqueId(level.id + "-room-" + std::to_string(k + 1), "");
    room.outline = found.outlines[k];
    level.rooms.push_back(std::move(room));
    ++summary.rooms;
  }
  simplified(describe("storey", storey.storey),
             "no space (IfcSpace) in it: its rooms are the free spaces its walls enclose, doors "
             "closed (" +
                 common::counted(found.outlines.size(), "room") + "; " +
                 common::counted(found.pockets, "pocket") + " under " +
                 fmt(bim::FreeSpaceOptions{}.min_area) + " m² left out)");
}

bim::Level Importer::level(int s, StoreySummary& summary) {
  const StoreyRecord& storey = storeys_[s];
  bim::Level level;
  level.id = summary.level_id;
  if (!storey.name.empty()) level.name = cleanText(storey.name, common::limits::kMaxTextBytes);
  level.ifc_guid = keptGlobalId(storey.global_id);
  level.elevation = storey.elevation;
  const std::map<int, std::pair<double, double>> base_top = levelWalls(s, summary, level);
  levelColumns(s, summary, level);
  // Openings on this level: in walls standing on it, whose home level (homeOf) is this one.
  std::map<int, std::vector<PlacedOpening>> along_wall;
  for (const auto& opening : openings_) {
    const auto wall = base_top.find(opening.wall);
    if (wall == base_top.end() || homeOf(opening) != s) continue;
    placed_.insert(&opening);
    placeOpening(opening, s, wall->second, along_wall[opening.wall], summary, level);
  }
  levelRooms(storey, summary, level);
  // The level's height: its walls' median top.
  std::vector<double> tops;
  for (const auto& wall : level.walls) tops.push_back(wall.height);
  std::sort(tops.begin(), tops.end());
  const double height = tops.empty() ? 3.0 : tops[tops.size() / 2];
  level.height = std::clamp(height, bim::limits::kMinSize, bim::limits::kMaxHeight);
  return level;
}

ImportResult Importer::run() {
  unit_ = bodies_.metresPerUnit();
  result_.schema = loaded_.header.schema;
  result_.application = loaded_.header.application;
  result_.metres_per_unit = unit_;
  readStoreys();
  readWalls();
  readColumns();
  readOpenings();
  readFlights();
  const std::vector<int> chosen = chooseLevels();
  // The plan holds coordinates within ±10 km (docs/formats.md, "Limits"); a model placed in
  // geographic or survey coordinates lies beyond, and says so here rather than as a broken rule.
  for (const auto& wall : walls_) {
    const double far =
        std::max(wall.fit.start.cwiseAbs().maxCoeff(), wall.fit.end.cwiseAbs().maxCoeff());
    if (far > bim::limits::kMaxCoordinate) {
      throw common::InputError(
          file_, "",
          describe(wall.kind, wall.element) + " lies " + fmt(far / 1000.0) +
              " km from the model's origin, beyond the plan's ±" +
              fmt(bim::limits::kMaxCoordinate / 1000.0) +
              " km: the model is placed in site or survey coordinates (its IfcSite's "
              "placement); move its site's placement near the origin in the authoring tool");
    }
  }
  is_level_.assign(storeys_.size(), false);
  for (int s : chosen) is_level_[s] = true;
  bim::Plan plan;
  for (int s = 0; s < int(storeys_.size()); ++s) {
    StoreySummary summary;
    summary.name = storeys_[s].name;
    summary.global_id = storeys_[s].global_id;
    summary.elevation = storeys_[s].elevation;
    summary.spaces = int(storeys_[s].spaces.size());
    if (std::find(chosen.begin(), chosen.end(), s) != chosen.end()) {
      summary.level_id = uniqueId(
          storeys_[s].name.empty() ? "storey-" + storeys_[s].global_id : storeys_[s].name, "");
      plan.levels.push_back(level(s, summary));
    } else {
      int walls_on = 0;
      for (const auto& wall : walls_) {
        walls_on += standsOn(wall.fit, storeys_[s].elevation) &&
                    wall.fit.top >= storeys_[s].elevation + kFullHeightWall;
      }
      int own = 0;
      for (const auto& wall : walls_) own += wall.storey == s;
      summary.why_not = walls_on == 0
                            ? "no wall rises " + fmt(kFullHeightWall) + " m above its floor"
                            : "no space (IfcSpace) in it, and the walls standing on it "
                              "are all other storeys' (" +
                                  common::counted(std::size_t(walls_on), "wall") + "; it has " +
                                  common::counted(std::size_t(own), "wall") + " of its own)";
    }
    result_.storeys.push_back(summary);
  }
  // What stands on no level imported is said too, unless its storey's summary says it.
  for (int w = 0; w < int(walls_.size()); ++w) {
    bool on_a_level = false;
    for (int s : chosen) on_a_level = on_a_level || wall_ids_.count({w, s});
    if (!on_a_level && is_level_[walls_[w].storey]) {
      dropped(describe(walls_[w].kind, walls_[w].element),
              "it stands on no level imported (from z " + fmt(walls_[w].fit.bottom) + " to " +
                  fmt(walls_[w].fit.top) + " m, it does not cross " + fmt(kStandingHeight) +
                  " m above any imported floor)");
    }
  }
  for (const auto& opening : openings_) {
    if (placed_.count(&opening)) continue;
    const WallRecord& wall = walls_[opening.wall];
    dropped(describe(opening.kind, opening.described) + " (in wall " + wall.global_id + ")",
            "its opening (from z " + fmt(opening.extent.z_min) + " to " +
                fmt(opening.extent.z_max) +
                " m) is on no imported level's floor in a part of its wall that stands there");
  }
  placeFlights(plan.levels);
  plan.name =
      cleanText(std::filesystem::path(file_).stem().string(), common::limits::kMaxTextBytes);
  bim::ImportedFrom& from = plan.imported_from.emplace();
  from.file =
      cleanText(std::filesystem::path(file_).filename().string(), common::limits::kMaxTextBytes);
  from.schema = result_.schema;
  from.application = cleanText(result_.application, common::limits::kMaxTextBytes);
  // As people write plans: each wall's height and base, no door rooms (the model gives none).
  result_.plan_json = bim::planToJson(
      plan, {.every_wall_height = true, .inferred_door_rooms = false, .names = true});
  return std::move(result_);
}

}  // namespace isg::ifc::importer
