#include "ifc/ifc_import.hpp"

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

namespace isg::ifc {
namespace {

using json = nlohmann::ordered_json;

// A wall stands on a level when its body crosses this height above the level's floor: where a
// legged robot's LiDAR (about 0.7 m up) looks and people walk. A slab edge, a kerb or the top of
// a wall of the storey below does not reach it; a toilet partition raised off the floor does.
constexpr double kStandingHeight = 1.0;
// A storey is a level a robot walks only if some wall on it rises this high above its floor: a
// roof with parapets or a foundation storey whose walls end at the ground floor is not.
constexpr double kFullHeightWall = 1.5;
// Below this an opening's bottom is on the floor (a threshold), above it an opening is a window.
constexpr double kFloorTolerance = 0.15;
// A doorway without a door must be at least this tall to be one a robot walks through.
constexpr double kMinDoorwayHeight = 1.8;
// Narrower openings are left out: no robot passes, and the sensor barely sees through.
constexpr double kMinOpeningWidth = 0.1;
// Less straight than this (WallFit::straightness: narrower than 90 % of its rectangle's width
// somewhere between its ends) is not a straight wall: L-shaped, curved, or several walls.
constexpr double kMinStraightness = 0.9;
// A simplification that moves a face by more than this is said in the log (the oracle test
// compares bounding boxes to the same tolerance).
constexpr double kReportedChange = 0.01;
// Thicker bodies are not walls the plan can hold as one straight wall.
constexpr double kMaxWallThickness = 2.0;
// Layer set and geometry disagree on the thickness by more than this: said in the log.
constexpr double kThicknessTolerance = 0.005;
// A flight's body starts on a level's floor and ends on another's within this (a little more
// than the 0.2 m riser a flight's last step may leave to the upper slab's edge).
constexpr double kFlightLevelTolerance = 0.25;
// A flight running into a wall by at most this at an end or a side is trimmed clear of it (its
// last tread or a stringer built into the wall); farther, the plan's rules refuse it.
constexpr double kFlightTrim = 0.1;

std::string fmt(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", std::abs(v) < 5e-4 ? 0.0 : v);
  return buffer;
}

// Ids and names of the plan: free of control characters (the plan forbids them) and within the
// plan's limits.
// Valid UTF-8 (JSON needs it; a header's bytes may be in any encoding): each byte that does not
// start or continue a well-formed sequence becomes U+FFFD.
std::string validUtf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = c < 0x80           ? 1
                         : (c >> 5) == 0x6  ? 2
                         : (c >> 4) == 0xE  ? 3
                         : (c >> 3) == 0x1E ? 4
                                            : 0;
    bool ok = length > 0 && i + length <= text.size();
    std::uint32_t code = length == 1   ? c
                         : length == 2 ? (c & 0x1F)
                         : length == 3 ? (c & 0x0F)
                                       : (c & 0x07);
    for (std::size_t k = 1; ok && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      ok = (next >> 6) == 0x2;
      code = (code << 6) | (next & 0x3F);
    }
    // Overlong forms, surrogates and code points beyond U+10FFFF are not UTF-8 either.
    static constexpr std::uint32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};
    ok = ok && code >= kLeast[length] && code <= 0x10FFFF && !(code >= 0xD800 && code <= 0xDFFF);
    if (ok) {
      out.append(text, i, length);
      i += length;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

std::string cleanText(std::string text, std::size_t max_bytes) {
  text = validUtf8(text);
  for (char& c : text) {
    if ((static_cast<unsigned char>(c) < 0x20) || c == 0x7F) c = ' ';
  }
  if (text.size() > max_bytes) {
    text.resize(max_bytes);
    // Not in the middle of a UTF-8 sequence.
    while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80) {
      text.pop_back();
    }
    if (!text.empty() && (static_cast<unsigned char>(text.back()) & 0x80)) text.pop_back();
  }
  return text;
}

std::string describe(const std::string& kind, const shared_ptr<IfcRoot>& object) {
  const std::string name = object ? labelText(object->m_Name) : "";
  return kind + " " + globalIdOf(object) + (name.empty() ? "" : " \"" + name + "\"");
}

struct WallRecord {
  shared_ptr<IfcElement> element;
  std::string kind;  // "wall", "curtain wall"
  std::string global_id, name;
  int storey = -1;  // index into the storeys, -1 outside any
  WallFit fit;
};

// A free-standing column: its body seen from above as a rectangle or a circle.
struct ColumnRecord {
  shared_ptr<IfcElement> element;
  std::string global_id, name;
  int storey = -1;
  bool round = false;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Zero();  // width along yaw, depth; round: diameter
  double yaw = 0.0;
  WallFit fit;  // bottom and top as for walls
};

struct OpeningRecord {
  std::string kind;               // "door", "window", "doorway", "opening"
  shared_ptr<IfcRoot> described;  // the door / window, or the opening itself
  std::string global_id, name;
  int wall = -1;
  AxisExtent extent;
};

struct FlightRecord {
  shared_ptr<IfcProduct> element;  // an IfcStairFlight, or an IfcStair without flights
  std::string kind;                // "stair flight" or "stair"
  std::string global_id, name;
  FlightFit fit;
};

struct SpaceRecord {
  shared_ptr<IfcSpace> space;
  std::optional<Footprint> footprint;
};

struct StoreyRecord {
  shared_ptr<IfcBuildingStorey> storey;
  std::string name, global_id;
  double elevation = 0.0;
  std::vector<shared_ptr<IfcProduct>> elements;
  std::vector<SpaceRecord> spaces;
};

template <typename Relation, typename Visit>
void forEachRelation(const std::vector<weak_ptr<Relation>>& relations, Visit visit) {
  for (const auto& weak : relations) {
    if (auto relation = weak.lock()) visit(relation);
  }
}

void collectSpaces(const shared_ptr<IfcObjectDefinition>& parent,
                   std::vector<shared_ptr<IfcSpace>>& spaces, int depth = 0) {
  if (depth > 8) return;
  forEachRelation(parent->m_IsDecomposedBy_inverse, [&](const shared_ptr<IfcRelAggregates>& rel) {
    for (const auto& child : rel->m_RelatedObjects) {
      if (auto space = dynamic_pointer_cast<IfcSpace>(child)) {
        spaces.push_back(space);
        collectSpaces(space, spaces, depth + 1);
      }
    }
  });
}

// The total thickness of the wall's material layer set, when it has one.
std::optional<double> layerSetThickness(const shared_ptr<IfcElement>& element, double unit) {
  std::optional<double> total;
  forEachRelation(element->m_HasAssociations_inverse, [&](const shared_ptr<IfcRelAssociates>& r) {
    auto material = dynamic_pointer_cast<IfcRelAssociatesMaterial>(r);
    if (!material) return;
    auto usage = dynamic_pointer_cast<IfcMaterialLayerSetUsage>(material->m_RelatingMaterial);
    if (!usage || !usage->m_ForLayerSet) return;
    double sum = 0.0;
    for (const auto& layer : usage->m_ForLayerSet->m_MaterialLayers) {
      if (layer && layer->m_LayerThickness) sum += layer->m_LayerThickness->m_value * unit;
    }
    total = sum;
  });
  return total;
}

// The body of an element, or of its parts (a curtain wall is often only its plates and members).
Mesh bodyWithParts(BodyReader& reader, const shared_ptr<IfcProduct>& product,
                   Eigen::Matrix4d* placement) {
  Body body = reader.read(product);
  if (placement) *placement = body.placement;
  if (!body.faces.empty()) return body.faces;
  Mesh parts;
  forEachRelation(product->m_IsDecomposedBy_inverse, [&](const shared_ptr<IfcRelAggregates>& rel) {
    for (const auto& child : rel->m_RelatedObjects) {
      if (auto part = dynamic_pointer_cast<IfcProduct>(child)) {
        Body part_body = reader.read(part);
        parts.insert(parts.end(), part_body.faces.begin(), part_body.faces.end());
      }
    }
  });
  return parts;
}

class Importer {
 public:
  Importer(const std::string& file, LoadedModel& loaded, const ImportOptions& options)
      : file_(file), loaded_(loaded), options_(options), bodies_(loaded) {}

  ImportResult run();

 private:
  void readStoreys();
  void readWalls();
  void readColumns();
  // The columns standing on the level's floor, into `level`.
  void levelColumns(int s, StoreySummary& summary, bim::Level& level);
  void readOpenings();
  void readFlights();
  void placeFlights(std::vector<bim::Level>& levels);
  // The flight trimmed by at most kFlightTrim at an end or a side for each wall of its two levels
  // it runs into, and the trims logged.
  FlightFit clearOfWalls(const FlightRecord& flight, const bim::Level& lower,
                         const bim::Level& upper);
  std::vector<int> chooseLevels();
  bim::Level level(int storey_index, StoreySummary& summary);
  // A level's walls (standing on its floor), into `level`; each wall's (base, top) above it.
  std::map<int, std::pair<double, double>> levelWalls(int s, StoreySummary& summary,
                                                      bim::Level& level);
  // The storey an opening belongs to: the highest level at or below its bottom that its wall
  // stands on; -1 for none.
  int homeOf(const OpeningRecord& opening) const;
  // An opening already placed along a wall: where, and which.
  struct PlacedOpening {
    double lo, hi;
    std::string id, kind;
  };
  // One opening of the level's wall (its (base, top) `base_top`) as a door or a window, cut to
  // the wall; dropped (and logged) where it does not fit or overlaps one `along_wall` holds.
  void placeOpening(const OpeningRecord& opening, int s, const std::pair<double, double>& base_top,
                    std::vector<PlacedOpening>& along_wall, StoreySummary& summary,
                    bim::Level& level);
  // The door's height (`head_room` above the wall's base) unless it is no door; logged.
  bool doorOf(const OpeningRecord& opening, const std::string& what, double above_base,
              double head_room, bim::Door& door);
  // The window's sill and height within its wall (`head` and `wall_height` above its base)
  // unless nothing is left; logged.
  bool windowOf(const OpeningRecord& opening, const std::string& what, double above_base,
                double head, double wall_height, bim::Window& window);
  // The storey's spaces with a closed outline as the level's rooms; the others logged.
  void levelRooms(const StoreyRecord& storey, StoreySummary& summary, bim::Level& level);
  // A storey without spaces: its rooms are the free spaces its walls enclose; logged.
  void freeSpaceRooms(const StoreyRecord& storey, StoreySummary& summary, bim::Level& level);
  std::string uniqueId(const std::string& wanted, const std::string& suffix);
  // The wall's body read as a straight prismatic wall, each way it falls short of one logged;
  // nullopt (logged as dropped) when it cannot be one.
  std::optional<WallFit> wallFit(const shared_ptr<IfcElement>& element, const std::string& kind,
                                 const std::string& what);
  // A door or window that no IfcRelFillsElement links to its opening, given to the empty opening
  // its body lies in (said); false when there is none.
  bool fillsByPlace(const shared_ptr<IfcProduct>& element, const std::string& kind);
  void dropped(const std::string& what, const std::string& why) {
    result_.log.push_back("dropped " + what + ": " + why);
  }
  void simplified(const std::string& what, const std::string& how) {
    result_.log.push_back("simplified " + what + ": " + how);
  }
  bool standsOn(const WallFit& fit, double elevation) const {
    return fit.bottom < elevation + kStandingHeight && fit.top > elevation + kStandingHeight;
  }

  std::string file_;
  LoadedModel& loaded_;
  const ImportOptions& options_;
  BodyReader bodies_;
  double unit_ = 1.0;
  std::vector<StoreyRecord> storeys_;
  std::map<BuildingEntity*, int> storey_of_;  // element → index in storeys_
  std::vector<WallRecord> walls_;
  std::vector<ColumnRecord> columns_;
  std::vector<OpeningRecord> openings_;
  std::vector<FlightRecord> flights_;
  std::set<std::string> used_ids_;
  // Each wall's id on each level it stands on.
  std::map<std::pair<int, int>, std::string> wall_ids_;
  std::vector<bool> is_level_;             // per storey: imported as a level
  std::set<const OpeningRecord*> placed_;  // openings that reached a level (kept or dropped)
  ImportResult result_;
};

std::string Importer::uniqueId(const std::string& wanted, const std::string& suffix) {
  std::string id = cleanText(wanted.empty() ? "unnamed" : wanted, common::limits::kMaxIdBytes - 24);
  if (id == bim::kOutside) id += "-";
  std::string candidate = id;
  if (used_ids_.count(candidate) && !suffix.empty()) candidate = id + "@" + cleanText(suffix, 20);
  for (int n = 2; used_ids_.count(candidate); ++n) candidate = id + "#" + std::to_string(n);
  used_ids_.insert(candidate);
  return candidate;
}

void Importer::readStoreys() {
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    auto storey = dynamic_pointer_cast<IfcBuildingStorey>(entity);
    if (!storey) continue;
    StoreyRecord record;
    record.storey = storey;
    record.global_id = globalIdOf(storey);
    record.name = labelText(storey->m_Name);
    if (storey->m_ObjectPlacement) {
      record.elevation = bodies_.placementOf(storey)(2, 3);
    } else if (storey->m_Elevation) {
      record.elevation = storey->m_Elevation->m_value * unit_;
    }
    std::vector<shared_ptr<IfcSpace>> spaces;
    collectSpaces(storey, spaces);
    // IFC aggregates a storey's spaces (IfcRelAggregates); some exporters (FreeCAD's through
    // IfcOpenShell) list them among its contained elements instead. Taken as its spaces all the
    // same, and said.
    forEachRelation(storey->m_ContainsElements_inverse,
                    [&](const shared_ptr<IfcRelContainedInSpatialStructure>& rel) {
                      for (const auto& e : rel->m_RelatedElements) {
                        if (!e) continue;
                        if (auto space = dynamic_pointer_cast<IfcSpace>(e)) {
                          if (std::find(spaces.begin(), spaces.end(), space) != spaces.end()) {
                            continue;
                          }
                          simplified(describe("space", space),
                                     "contained in its storey (IfcRelContainedInSpatialStructure) "
                                     "rather than aggregated (IfcRelAggregates): taken as a space "
                                     "of the storey");
                          spaces.push_back(space);
                          collectSpaces(space, spaces, 1);
                          continue;
                        }
                        record.elements.push_back(e);
                      }
                    });
    // Elements placed in a space belong to the space's storey.
    for (const auto& space : spaces) {
      record.spaces.push_back({space, footprintOf(bodies_.read(space).faces)});
      forEachRelation(space->m_ContainsElements_inverse,
                      [&](const shared_ptr<IfcRelContainedInSpatialStructure>& rel) {
                        for (const auto& e : rel->m_RelatedElements) {
                          if (e) record.elements.push_back(e);
                        }
                      });
    }
    // The floor people stand on is where the storey's rooms begin: IFC storey elevations are
    // sometimes the structural slab's, or a tool's reference level below it.
    std::vector<double> floors;
    for (const auto& space : record.spaces) {
      if (space.footprint) floors.push_back(space.footprint->z);
    }
    if (!floors.empty()) {
      std::nth_element(floors.begin(), floors.begin() + floors.size() / 2, floors.end());
      const double floor = floors[floors.size() / 2];
      if (std::abs(floor - record.elevation) > 0.01) {
        simplified("storey \"" + record.name + "\" " + record.global_id,
                   "its elevation is " + fmt(record.elevation) + " m, its spaces' floor " +
                       fmt(floor) + " m: the level's floor is taken where its rooms are");
        record.elevation = floor;
      }
    }
    storeys_.push_back(std::move(record));
  }
  if (storeys_.empty()) {
    throw common::InputError(file_, "", "no IfcBuildingStorey: the model has no storey to import");
  }
  std::stable_sort(
      storeys_.begin(), storeys_.end(),
      [](const StoreyRecord& a, const StoreyRecord& b) { return a.elevation < b.elevation; });
  // The first storey that contains an element is its storey (walls and columns look it up).
  for (int s = 0; s < int(storeys_.size()); ++s) {
    for (const auto& e : storeys_[s].elements) storey_of_.emplace(e.get(), s);
  }
}

std::optional<WallFit> Importer::wallFit(const shared_ptr<IfcElement>& element,
                                         const std::string& kind, const std::string& what) {
  Eigen::Matrix4d placement;
  const Mesh body = bodyWithParts(bodies_, element, &placement);
  const std::vector<std::string> non_positive = nonPositiveLengths(element);
  std::string lengths;
  for (const auto& n : non_positive) lengths += (lengths.empty() ? "" : ", ") + n;
  if (body.empty()) {
    dropped(what,
            "no body geometry IFC++ could build" +
                (lengths.empty() ? std::string()
                                 : " (IFC requires these lengths positive: " + lengths + ")"));
    return std::nullopt;
  }
  if (!lengths.empty()) {
    simplified(what, "IFC requires these lengths of its body positive: " + lengths +
                         "; IFC++ builds a negative one mirrored, and that body is used");
  }
  const Eigen::Vector2d own_x = placement.block<2, 1>(0, 0);
  const auto fit = fitWall(body, own_x);
  if (!fit || fit->thickness < bim::limits::kMinSize ||
      (fit->end - fit->start).norm() < bim::limits::kMinSize) {
    dropped(what, "its body has no extent seen from above");
    return std::nullopt;
  }
  if (fit->thickness > kMaxWallThickness) {
    dropped(what, "thicker than " + fmt(kMaxWallThickness) + " m seen from above (" +
                      fmt(fit->thickness) + " m): not one straight wall");
    return std::nullopt;
  }
  if (fit->straightness < kMinStraightness) {
    dropped(what, "not straight: seen from above it fills its " + fmt(fit->thickness) +
                      " m wide rectangle too little (straightness " +
                      std::to_string(int(std::round(fit->straightness * 100))) +
                      " %; an L-shaped or curved wall); the plan holds straight walls only");
    return std::nullopt;
  }
  // The rectangle covers more than the body: by a strip over kReportedChange wide, averaged
  // along the wall, when the ends are cut at an angle.
  if ((1.0 - fit->rectangle_fill) * (fit->end - fit->start).norm() > kReportedChange) {
    simplified(what, "its ends are not square (mitred or angled joints; it fills " +
                         std::to_string(int(std::round(fit->rectangle_fill * 100))) +
                         " % of its rectangle): taken as its rectangle, " +
                         fmt((fit->end - fit->start).norm()) + " m long");
  }
  if (fit->top - fit->bottom < bim::limits::kMinSize) {
    dropped(what, "no height left between its highest bottom and lowest top");
    return std::nullopt;
  }
  if (fit->highest_top - fit->top > kReportedChange) {
    simplified(what, "its top varies from " + fmt(fit->top) + " to " + fmt(fit->highest_top) +
                         " m (a gable or a sloped top): taken at its lowest, " + fmt(fit->top) +
                         " m, so that no wall stands where there is none");
  }
  if (fit->bottom - fit->lowest_bottom > kReportedChange) {
    simplified(what, "its bottom varies from " + fmt(fit->lowest_bottom) + " to " +
                         fmt(fit->bottom) + " m or more: taken at its median, " + fmt(fit->bottom) +
                         " m");
  }
  if (kind == "curtain wall") {
    simplified(what, "a curtain wall: imported as an opaque wall " + fmt(fit->thickness) +
                         " m thick (the simulated sensor does not see through glass)");
  }
  if (const auto layers = layerSetThickness(element, unit_)) {
    if (std::abs(*layers - fit->thickness) > kThicknessTolerance) {
      simplified(what, "its layer set is " + fmt(*layers) + " m thick, its body " +
                           fmt(fit->thickness) + " m: the body's thickness is kept");
    }
  }
  return fit;
}

void Importer::readWalls() {
  std::map<int, std::size_t> walls_in_storey;
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    auto element = dynamic_pointer_cast<IfcElement>(entity);
    if (!element) continue;
    std::string kind;
    if (dynamic_pointer_cast<IfcWall>(entity)) {
      kind = "wall";
    } else if (dynamic_pointer_cast<IfcCurtainWall>(entity)) {
      kind = "curtain wall";
    } else {
      continue;
    }
    // A wall that is itself a part of a curtain wall (or another wall) is read with its whole.
    bool is_part = false;
    forEachRelation(element->m_Decomposes_inverse, [&](const shared_ptr<IfcRelAggregates>& rel) {
      if (dynamic_pointer_cast<IfcWall>(rel->m_RelatingObject) ||
          dynamic_pointer_cast<IfcCurtainWall>(rel->m_RelatingObject)) {
        is_part = true;
      }
    });
    if (is_part) continue;
    const std::string what = describe(kind, element);
    auto s = storey_of_.find(entity.get());
    if (s == storey_of_.end()) {
      dropped(what, "not contained in a building storey");
      continue;
    }
    const auto fit = wallFit(element, kind, what);
    if (!fit) continue;
    WallRecord wall;
    wall.element = element;
    wall.kind = kind;
    wall.global_id = globalIdOf(element);
    wall.name = labelText(element->m_Name);
    wall.storey = s->second;
    wall.fit = *fit;
    // Counted as they are read: a storey past the level's limit stops the import here, before
    // the rest of its walls are fitted.
    if (++walls_in_storey[wall.storey] > bim::limits::kMaxWallsPerLevel) {
      throw common::InputError(
          file_, "",
          "storey \"" + storeys_[std::size_t(wall.storey)].name + "\": more than " +
              std::to_string(bim::limits::kMaxWallsPerLevel) + " walls; at most " +
              std::to_string(bim::limits::kMaxWallsPerLevel) +
              " a level are supported (docs/formats.md, Limits)");
    }
    walls_.push_back(std::move(wall));
  }
}

void Importer::readColumns() {
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    auto element = dynamic_pointer_cast<IfcColumn>(entity);
    if (!element) continue;
    const std::string what = describe("column", element);
    auto s = storey_of_.find(entity.get());
    if (s == storey_of_.end()) {
      dropped(what, "not contained in a building storey");
      continue;
    }
    Eigen::Matrix4d placement;
    const Mesh body = bodyWithParts(bodies_, element, &placement);
    const auto fit = body.empty() ? std::nullopt : fitWall(body, placement.block<2, 1>(0, 0));
    if (!fit || fit->thickness < bim::limits::kMinSize ||
        (fit->end - fit->start).norm() < bim::limits::kMinSize) {
      dropped(what, "no body geometry seen from above");
      continue;
    }
    ColumnRecord column;
    column.element = element;
    column.global_id = globalIdOf(element);
    column.name = labelText(element->m_Name);
    column.storey = s->second;
    column.fit = *fit;
    const Eigen::Vector2d along = fit->end - fit->start;
    const double length = along.norm();
    if (length > kMaxWallThickness || fit->thickness > kMaxWallThickness) {
      dropped(what, "wider than " + fmt(kMaxWallThickness) + " m seen from above (" + fmt(length) +
                        " × " + fmt(fit->thickness) + " m): not a column");
      continue;
    }
    if (fit->top - fit->bottom < bim::limits::kMinSize) {
      dropped(what, "no height left between its highest bottom and lowest top");
      continue;
    }
    column.center = 0.5 * (fit->start + fit->end);
    // A circle fills π/4 of its square (a polygon of 16 or more sides between 0.77 and 0.80): a
    // body whose rectangle is within 5 % of a square and which fills 0.74–0.82 of it is round.
    const double aspect = std::max(length, fit->thickness) / std::min(length, fit->thickness);
    if (aspect < 1.05 && fit->rectangle_fill > 0.74 && fit->rectangle_fill < 0.82) {
      column.round = true;
      const double d = 0.5 * (length + fit->thickness);
      column.size = {d, d};
    } else {
      column.size = {length, fit->thickness};
      column.yaw = std::atan2(along.y(), along.x());
      if (fit->rectangle_fill < 0.9) {
        simplified(what, "it fills " + std::to_string(int(std::round(fit->rectangle_fill * 100))) +
                             " % of its rectangle seen from above (a steel section or an "
                             "L-shaped column): taken as its rectangle, " +
                             fmt(length) + " × " + fmt(fit->thickness) + " m");
      }
    }
    columns_.push_back(std::move(column));
  }
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
    level.columns.push_back(std::move(column));
    ++summary.columns;
  }
}

bool Importer::fillsByPlace(const shared_ptr<IfcProduct>& element, const std::string& kind) {
  if (!element) return false;
  const Mesh body = bodies_.read(element).faces;
  if (body.empty()) return false;
  // The empty opening of an imported wall that the element's body lies in: its centre within the
  // wall's thickness of the wall's axis, and within the opening's extent along the wall.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& face : body) {
    for (const auto& p : face) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  for (auto& opening : openings_) {
    if (opening.kind != "opening") continue;
    const WallFit& fit = walls_[std::size_t(opening.wall)].fit;
    const Eigen::Vector2d axis = fit.end - fit.start;
    if (axis.norm() < 1e-9) continue;
    const Eigen::Vector2d u = axis.normalized();
    const Eigen::Vector2d d = centre.head<2>() - fit.start;
    const double along = d.dot(u), across = std::abs(d.x() * u.y() - d.y() * u.x());
    if (across > 0.5 * fit.thickness + 0.05 || along < opening.extent.along_min ||
        along > opening.extent.along_max || centre.z() < opening.extent.z_min ||
        centre.z() > opening.extent.z_max) {
      continue;
    }
    const auto root = dynamic_pointer_cast<IfcRoot>(element);
    simplified(describe(kind, root), "no IfcRelFillsElement names its opening: it fills opening " +
                                         opening.global_id + " of wall " +
                                         walls_[std::size_t(opening.wall)].global_id +
                                         ", in which it lies");
    opening.kind = kind;
    opening.described = root;
    opening.global_id = globalIdOf(root);
    opening.name = labelText(root->m_Name);
    return true;
  }
  return false;
}

void Importer::readOpenings() {
  std::set<BuildingEntity*> filled;  // doors and windows found in an opening
  for (int w = 0; w < int(walls_.size()); ++w) {
    const WallRecord& wall = walls_[w];
    forEachRelation(
        wall.element->m_HasOpenings_inverse, [&](const shared_ptr<IfcRelVoidsElement>& rel) {
          auto opening = dynamic_pointer_cast<IfcOpeningElement>(rel->m_RelatedOpeningElement);
          if (!opening) return;
          OpeningRecord record;
          record.wall = w;
          record.described = opening;
          forEachRelation(
              opening->m_HasFillings_inverse, [&](const shared_ptr<IfcRelFillsElement>& fill) {
                const auto& element = fill->m_RelatedBuildingElement;
                if (dynamic_pointer_cast<IfcDoor>(element)) {
                  record.kind = "door", record.described = element;
                } else if (dynamic_pointer_cast<IfcWindow>(element) && record.kind.empty()) {
                  record.kind = "window", record.described = element;
                }
                if (element) filled.insert(element.get());
              });
          const std::string what =
              describe(record.kind.empty() ? "opening" : record.kind, record.described) +
              " (in wall " + wall.global_id + ")";
          if (opening->m_PredefinedType &&
              opening->m_PredefinedType->m_enum == IfcOpeningElementTypeEnum::ENUM_RECESS) {
            dropped(what, "a recess, not an opening through the wall");
            return;
          }
          const Mesh body = bodies_.read(opening).faces;
          const auto extent = extentAlong(body, wall.fit.start, wall.fit.end);
          if (!extent) {
            dropped(what, "its opening has no body geometry");
            return;
          }
          record.extent = *extent;
          record.global_id = globalIdOf(record.described);
          record.name = labelText(record.described->m_Name);
          if (record.kind.empty()) record.kind = "opening";
          openings_.push_back(std::move(record));
        });
  }
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    const bool door = dynamic_pointer_cast<IfcDoor>(entity) != nullptr;
    const bool window = dynamic_pointer_cast<IfcWindow>(entity) != nullptr;
    if ((!door && !window) || filled.count(entity.get())) continue;
    if (fillsByPlace(dynamic_pointer_cast<IfcProduct>(entity), door ? "door" : "window")) continue;
    dropped(describe(door ? "door" : "window", dynamic_pointer_cast<IfcRoot>(entity)),
            "it fills no opening of an imported wall (a partition or free-standing door, or its "
            "wall was left out)");
  }
}

void Importer::readFlights() {
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    std::string kind;
    if (dynamic_pointer_cast<IfcStairFlight>(entity)) {
      kind = "stair flight";
    } else if (auto stair = dynamic_pointer_cast<IfcStair>(entity)) {
      // A stair is read through its flights when it has them (its landings are floor).
      bool has_flights = false;
      forEachRelation(stair->m_IsDecomposedBy_inverse, [&](const shared_ptr<IfcRelAggregates>& r) {
        for (const auto& part : r->m_RelatedObjects) {
          has_flights = has_flights || dynamic_pointer_cast<IfcStairFlight>(part) != nullptr;
        }
      });
      if (has_flights) continue;
      kind = "stair";
    } else {
      continue;
    }
    auto element = dynamic_pointer_cast<IfcProduct>(entity);
    const std::string what = describe(kind, element);
    const Mesh body = bodyWithParts(bodies_, element, nullptr);
    const auto fit = body.empty() ? std::nullopt : fitFlight(body);
    if (!fit) {
      dropped(what, "no body geometry IFC++ could build");
      continue;
    }
    flights_.push_back({element, kind, globalIdOf(element), labelText(element->m_Name), *fit});
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

}  // namespace

namespace {

// The steps that run IFC++: the model read, the elements fitted, the plan's JSON made (no parse).
ImportResult importWithIfcpp(const std::string& file, std::string text,
                             const ImportOptions& options) {
  LoadedModel loaded = loadModel(file, std::move(text));
  Importer importer(file, loaded, options);
  ImportResult result = importer.run();
  result.reader_errors = loaded.messages.errors;
  return result;
}

// What crosses from the child process to the parent.
nlohmann::json resultToMessage(const ImportResult& r) {
  nlohmann::json storeys = nlohmann::json::array();
  for (const auto& s : r.storeys) {
    storeys.push_back({{"name", s.name},
                       {"global_id", s.global_id},
                       {"elevation", s.elevation},
                       {"level_id", s.level_id},
                       {"why_not", s.why_not},
                       {"counts",
                        {s.walls, s.walls_from_other_storeys, s.doors, s.windows, s.rooms, s.spaces,
                         s.columns}}});
  }
  return {{"ok", true},
          {"plan", r.plan_json.dump()},
          {"schema", r.schema},
          {"application", r.application},
          {"metres_per_unit", r.metres_per_unit},
          {"log", r.log},
          {"storeys", storeys},
          {"reader_errors", r.reader_errors}};
}

ImportResult resultFromMessage(const nlohmann::json& m) {
  ImportResult r;
  r.plan_json = nlohmann::ordered_json::parse(m.at("plan").get<std::string>());
  r.schema = m.at("schema").get<std::string>();
  r.application = m.at("application").get<std::string>();
  r.metres_per_unit = m.at("metres_per_unit").get<double>();
  r.log = m.at("log").get<std::vector<std::string>>();
  r.reader_errors = m.at("reader_errors").get<std::vector<std::string>>();
  for (const auto& s : m.at("storeys")) {
    StoreySummary summary;
    summary.name = s.at("name").get<std::string>();
    summary.global_id = s.at("global_id").get<std::string>();
    summary.elevation = s.at("elevation").get<double>();
    summary.level_id = s.at("level_id").get<std::string>();
    summary.why_not = s.at("why_not").get<std::string>();
    const auto& c = s.at("counts");
    summary.walls = c.at(0), summary.walls_from_other_storeys = c.at(1), summary.doors = c.at(2);
    summary.windows = c.at(3), summary.rooms = c.at(4), summary.spaces = c.at(5);
    summary.columns = c.at(6);
    r.storeys.push_back(summary);
  }
  return r;
}

void writeAll(int fd, const std::string& bytes) {
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

std::string readAll(int fd) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return bytes;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

// IFC++ is not robust against malformed models (ci/fuzz found null dereferences in its geometry
// code, and leaks): it runs in a child process, so that whatever it does to a bad file, isg
// reports the file and exits 1 with nothing written.
ImportResult importInChildProcess(const std::string& file, std::string text,
                                  const ImportOptions& options) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot make a pipe for the IFC reader");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    throw std::runtime_error("cannot start the IFC reader's process");
  }
  if (pid == 0) {
    ::close(fds[0]);
    // The child dies of what kills it, whatever handlers the parent installed (isg's interrupt
    // flag, a sanitizer's or libFuzzer's crash reports): the parent reads its signal, a Ctrl-C
    // stops it at once, and a crash inside IFC++ is the parent's to report.
    for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGINT, SIGTERM, SIGHUP}) {
      std::signal(signal, SIG_DFL);
    }
    nlohmann::json message;
    try {
      message = resultToMessage(importWithIfcpp(file, std::move(text), options));
    } catch (const common::InputError& e) {
      message = {{"ok", false}, {"pointer", e.pointer()}, {"reason", e.reason()}};
    } catch (const std::exception& e) {
      message = {{"ok", false}, {"internal", e.what()}};
    }
    writeAll(fds[1], message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    ::close(fds[1]);
    ::_exit(0);  // neither the parent's exit handlers nor its buffers
  }
  ::close(fds[1]);
  const std::string bytes = readAll(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGINT || signal == SIGTERM || signal == SIGHUP) throw ImportInterrupted(signal);
    throw common::InputError(file, "",
                             "IFC++ stopped with signal " + std::to_string(signal) + " (" +
                                 strsignal(signal) +
                                 ") while reading the model: it is malformed, or uses what IFC++ "
                                 "(Debian's libifcplusplus) cannot read");
  }
  const nlohmann::json message = nlohmann::json::parse(bytes, nullptr, false);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || message.is_discarded() ||
      !message.is_object()) {
    throw common::InputError(file, "",
                             "IFC++ stopped while reading the model (exit status " +
                                 std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                                 "): it is malformed, or uses what IFC++ cannot read");
  }
  if (!message.value("ok", false)) {
    if (message.contains("internal")) {
      throw std::runtime_error("the IFC import: " + message["internal"].get<std::string>());
    }
    throw common::InputError(file, message.value("pointer", ""), message.value("reason", ""));
  }
  return resultFromMessage(message);
}

// When `error` is at a flight of stairs (/levels/L/stairs/K...), removes that flight from the
// plan, logs why and returns true.
bool dropRefusedFlight(ImportResult& result, const common::InputError& error) {
  const std::string& pointer = error.pointer();
  std::size_t level = 0, stair = 0;
  char rest = 0;
  if (std::sscanf(pointer.c_str(), "/levels/%zu/stairs/%zu%c", &level, &stair, &rest) < 2) {
    return false;
  }
  auto& levels = result.plan_json["levels"];
  if (level >= levels.size() || !levels[level].contains("stairs")) return false;
  auto& stairs = levels[level]["stairs"];
  if (stair >= stairs.size()) return false;
  result.log.push_back("dropped stair flight " + stairs[stair]["id"].get<std::string>() + " (" +
                       stairs[stair].value("name", std::string()) +
                       "): the plan's rules for stairs refuse it: " + error.reason());
  stairs.erase(stair);
  if (stairs.empty()) levels[level].erase("stairs");
  return true;
}

}  // namespace

ImportInterrupted::ImportInterrupted(int signal)
    : std::runtime_error("stopped by signal " + std::to_string(signal)), signal_(signal) {}

ImportResult importIfcText(const std::string& file, std::string text,
                           const ImportOptions& options) {
  // The quick checks of the file's text here, with their exact messages; IFC++ in the child.
  readStepHeader(file, text);
  checkStepStrings(file, text);
  // More walls than every storey may hold between them is refused before IFC++ builds them
  // (10⁵ walls took 9 s and 350 MB to reach the plan's own limit).
  const std::size_t walls = countInstances(
      text, {"IFCWALL", "IFCWALLSTANDARDCASE", "IFCWALLELEMENTEDCASE", "IFCCURTAINWALL"});
  const std::size_t storeys = std::max<std::size_t>(1, countInstances(text, {"IFCBUILDINGSTOREY"}));
  if (walls > storeys * bim::limits::kMaxWallsPerLevel) {
    throw common::InputError(
        file, "",
        std::to_string(walls) + " walls in " + common::counted(storeys, "storey") + "; at most " +
            std::to_string(bim::limits::kMaxWallsPerLevel) +
            " a level are supported (docs/formats.md, Limits), however they are spread");
  }
  ImportResult result = importInChildProcess(file, std::move(text), options);
  // The plan is read back by the plan's own parser: what is written is a plan isg accepts.
  // A flight the plan's rules refuse (too steep or narrow for a legged robot, into a wall) is
  // dropped with the parser's reason, and the plan read again.
  for (;;) {
    const nlohmann::json document = nlohmann::json::parse(result.plan_json.dump());
    result.warnings.clear();
    const common::JsonSource source{file, &result.warnings};
    try {
      result.plan = bim::parsePlan(common::JsonNode(document, "", source));
      return result;
    } catch (const common::InputError& e) {
      if (!dropRefusedFlight(result, e)) {
        throw common::InputError(file, "",
                                 "the plan imported from it breaks a rule of the plan format at " +
                                     e.pointer() + ": " + e.reason());
      }
    }
  }
}

ImportResult importIfc(const std::string& path, const ImportOptions& options) {
  return importIfcText(path, common::readCheckedFile(path, kMaxIfcBytes), options);
}

}  // namespace isg::ifc
