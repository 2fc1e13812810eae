#pragma once

// The IFC import's own parts (ifc/ifc_reader.cpp reads the model's elements into records,
// ifc/level_builder.cpp turns them into the plan's levels): the thresholds, the records and the
// Importer that holds them. Included only by this module's .cpp files: it includes IFC++
// (ifc/ifcpp_model.hpp), whose names are global.

#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcElement.h>
#include <ifcpp/IFC4/include/IfcObjectDefinition.h>
#include <ifcpp/IFC4/include/IfcSpace.h>

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "bim/plan.hpp"
#include "ifc/ifc_import.hpp"
#include "ifc/ifcpp_model.hpp"

namespace isg::ifc::importer {

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

// A length in metres for the log, to the millimetre.
std::string fmt(double v);

// Valid UTF-8 (JSON needs it; a header's bytes may be in any encoding): each byte that does not
// start or continue a well-formed sequence becomes U+FFFD.
std::string validUtf8(const std::string& text);

// Ids and names of the plan: free of control characters (the plan forbids them) and within
// `max_bytes`, never cut inside a UTF-8 sequence.
std::string cleanText(std::string text, std::size_t max_bytes);

// An element as the log names it: its kind, GlobalId and name.
std::string describe(const std::string& kind, const shared_ptr<IfcRoot>& object);

// The spaces an object aggregates, and theirs, to a depth of 8.
void collectSpaces(const shared_ptr<IfcObjectDefinition>& parent,
                   std::vector<shared_ptr<IfcSpace>>& spaces, int depth = 0);

// The total thickness of the wall's material layer set, when it has one.
std::optional<double> layerSetThickness(const shared_ptr<IfcElement>& element, double unit);

// The body of an element, or of its parts (a curtain wall is often only its plates and members).
Mesh bodyWithParts(BodyReader& reader, const shared_ptr<IfcProduct>& product,
                   Eigen::Matrix4d* placement);

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

}  // namespace isg::ifc::importer
