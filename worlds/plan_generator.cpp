#include "worlds/plan_generator.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <queue>
#include <random>
#include <set>
#include <stdexcept>

#include "bim/plan.hpp"
#include "bim/plan_json.hpp"
#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"
#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "worlds/millimetres.hpp"
#include "worlds/parking_generator.hpp"
#include "worlds/plan_lean.hpp"
#include "worlds/segment_distance.hpp"
#include "worlds/site_generator.hpp"

namespace isg::worlds {

namespace {

// The width of an office door, and the narrowest opening the robot is sent through.
constexpr double kOfficeDoorWidth = 0.9;

using nlohmann::json;

enum class Kind { kOffice, kCorridor, kHall };

// One rectangle of the floor: an office, a corridor piece or a hall.
struct Space {
  Kind kind = Kind::kOffice;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double door_fraction = -1.0;  // where along its corridor side the door sits; < 0: by the rule
};

class Floor {
 public:
  Floor(const GeneratorSpec& spec, std::mt19937_64& rng) : spec_(spec), rng_(rng) {}

  void add(Kind kind, double x0, double y0, double x1, double y1, double door_fraction = -1.0) {
    spaces.push_back({kind, mm(x0), mm(y0), mm(x1), mm(y1), door_fraction});
  }

  // Office widths filling `length`: the mean width, spread by ±size_spread, the last one taking
  // what is left (merged into its neighbour when that would be under 60 % of the mean).
  std::vector<double> widths(double length) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double mean = spec_.room_width;
    std::vector<double> out;
    double left = length;
    while (left > 1e-9) {
      double w = mean * (1.0 + spec_.size_spread * unit(rng_));
      if (left - w < 0.6 * mean) w = left;
      out.push_back(w);
      left -= w;
    }
    if (out.size() > 1 && out.back() < 0.6 * mean) {
      out[out.size() - 2] += out.back();
      out.pop_back();
    }
    return out;
  }

  // Offices side by side along x over [a, b], from y0 to y1.
  void officesAlongX(double a, double b, double y0, double y1) {
    if (b - a < 1.6) return;  // too short for an office with a door: left outside
    double x = a;
    for (double w : widths(b - a)) {
      add(Kind::kOffice, x, y0, x + w, y1);
      x += w;
    }
  }

  // Offices one above the other along y over [a, b], from x0 to x1.
  void officesAlongY(double a, double b, double x0, double x1) {
    if (b - a < 1.6) return;
    double y = a;
    for (double w : widths(b - a)) {
      add(Kind::kOffice, x0, y, x1, y + w);
      y += w;
    }
  }

  std::vector<Space> spaces;

 private:
  const GeneratorSpec& spec_;
  std::mt19937_64& rng_;
};

int roomsOr(int rooms, int fallback) { return rooms > 0 ? rooms : fallback; }

// Bands of offices on both sides of a middle space (a corridor, or a hall), stacked back to back,
// joined by a spine corridor across the bands in the middle. As many bands as keep the floor
// about twice as long as it is deep.
void bandedFloor(const GeneratorSpec& s, Floor& floor, Kind middle, int default_rooms) {
  const int n = roomsOr(s.rooms, default_rooms);
  const double d = s.room_depth, c = s.corridor_width;
  const auto middleDepth = [&](double length) {
    return middle == Kind::kHall ? mm(std::clamp(length / 3.0, 6.0, 12.0)) : c;
  };
  const double band_guess = 2 * d + middleDepth(n * s.room_width / 2.0);
  const int bands = std::max(1, int(std::lround(std::sqrt(n * s.room_width / (4.0 * band_guess)))));
  const int per_row = std::max(2, (n + 2 * bands - 1) / (2 * bands));
  const double length = mm(per_row * s.room_width);
  const double m = middleDepth(length);
  const double spine = mm(0.5 * (length - c));
  for (int b = 0; b < bands; ++b) {
    const double base = b * (2 * d + m);
    // Rows next to the spine are cut by it.
    auto row = [&](double y0, double y1, bool cut) {
      if (!cut) return floor.officesAlongX(0, length, y0, y1);
      floor.officesAlongX(0, spine, y0, y1);
      floor.officesAlongX(spine + c, length, y0, y1);
    };
    row(base, base + d, b > 0);
    floor.add(middle, 0, base + d, length, base + d + m);
    row(base + d + m, base + 2 * d + m, b + 1 < bands);
    if (b + 1 < bands) {
      floor.add(Kind::kCorridor, spine, base + d + m, spine + c, base + 2 * d + m + d);
    }
  }
}

// How many bands of offices (two rows and a corridor) an L, T or U's base and each of its arms
// are wide. One up to kSingleBandRooms offices (every such floor as it always was); beyond, about
// as many as make each arm as wide as it is long (0.85 of that: the corner blocks hold offices
// too), so that the floor fills much of its bounding box. A single corridor of 300 offices is a
// wing 300 m long, and the route grid covers such a box only with cells too coarse for a doorway
// (sim/occupancy_grid.hpp, kMaxCells).
int armBands(int rooms, int arms, const GeneratorSpec& s) {
  constexpr int kSingleBandRooms = 200;
  if (rooms <= kSingleBandRooms) return 1;
  const double band = 2 * s.room_depth + s.corridor_width;
  const double square = std::sqrt(rooms * s.room_width / (2.0 * (arms + 1) * band));
  return std::max(2, int(std::lround(0.85 * square)));
}

// L, T or U: a base of offices on both sides of a corridor, with one or two arms (offices on both
// sides of a corridor) rising from its corridor. Large floors stack `bands` of them: the base's
// bands joined by a spine corridor across them (as bandedFloor's), each arm `bands` side by side,
// each of their corridors opening onto the base's top corridor.
void armedFloor(const GeneratorSpec& s, Floor& floor, char shape) {
  const int n = roomsOr(s.rooms, 24);
  const int arms = shape == 'U' ? 2 : 1;
  const int bands = armBands(n, arms, s);
  const double d = s.room_depth, c = s.corridor_width, band = 2 * d + c, arm = bands * band;
  int per_arm_side = std::max(2, int(std::lround(n / (2.0 * (arms + 1)))));
  int per_band_row = std::max(2, (n - 2 * arms * per_arm_side + 1) / 2);
  if (bands > 1) {
    // The base's rows under each arm (all but the top one) hold offices too; what is left is
    // shared by the arms and the base beside them, each as long as an arm rises.
    const double corners = arms * (2 * bands - 1) * std::round(arm / s.room_width);
    per_arm_side = std::max(2, int(std::lround((n - corners) / (2.0 * bands * (arms + 1)))));
    per_band_row = per_arm_side;
  }
  const double length = mm(per_band_row * s.room_width + arms * arm);
  const double rise = mm(per_arm_side * s.room_width);
  std::vector<double> arm_at;
  if (shape == 'L') arm_at = {0.0};
  if (shape == 'T') arm_at = {mm(0.5 * (length - arm))};
  if (shape == 'U') arm_at = {0.0, mm(length - arm)};
  const double spine = mm(0.5 * (length - c));
  // The base's bands below the top one, each joined to the next by the spine.
  for (int b = 0; b + 1 < bands; ++b) {
    const double y = b * band;
    auto row = [&](double y0, double y1) {
      floor.officesAlongX(0, spine, y0, y1);
      floor.officesAlongX(spine + c, length, y0, y1);
    };
    if (b == 0) {
      floor.officesAlongX(0, length, y, y + d);
    } else {
      row(y, y + d);
    }
    floor.add(Kind::kCorridor, 0, y + d, length, y + d + c);
    row(y + d + c, y + band);
    floor.add(Kind::kCorridor, spine, y + d + c, spine + c, y + band + d);
  }
  // The top band: its south row (cut by the spine when there are bands below), its corridor, and
  // its north row between the arms.
  const double y = (bands - 1) * band;
  if (bands == 1) {
    floor.officesAlongX(0, length, 0, d);
  } else {
    floor.officesAlongX(0, spine, y, y + d);
    floor.officesAlongX(spine + c, length, y, y + d);
  }
  const double top = y + d + c;
  floor.add(Kind::kCorridor, 0, y + d, length, top);
  double x = 0.0;
  for (double a : arm_at) {
    floor.officesAlongX(x, a, top, top + d);
    x = a + arm;
    for (int k = 0; k < bands; ++k) {
      const double x0 = a + k * band;
      floor.officesAlongY(top, top + rise, x0, x0 + d);
      floor.add(Kind::kCorridor, x0 + d, top, x0 + d + c, top + rise);
      floor.officesAlongY(top, top + rise, x0 + d + c, x0 + band);
    }
  }
  floor.officesAlongX(x, length, top, top + d);
}

// A hotel floor: identical rooms on both sides of one corridor. The seed draws the room size
// (±15 % of the given width and depth), where the doors sit and, with the asymmetry, which two
// neighbouring north rooms are one suite, so that a half turn does not map the floor onto itself.
void hotel(const GeneratorSpec& s, Floor& floor, std::mt19937_64& rng) {
  const int per_row = std::max(2, (roomsOr(s.rooms, 22) + 1) / 2);
  std::uniform_real_distribution<double> scale(0.85, 1.15), placement(0.2, 0.8);
  const double w = mm(s.room_width * scale(rng)), d = mm(s.room_depth * scale(rng));
  const double c = s.corridor_width;
  const double drawn = placement(rng);
  const double fraction = s.doors == "center" ? 0.5 : s.doors == "corner" ? 0.1 : drawn;
  const int suite = std::uniform_int_distribution<int>(0, per_row - 2)(rng);
  for (int i = 0; i < per_row; ++i) floor.add(Kind::kOffice, i * w, 0, (i + 1) * w, d, fraction);
  floor.add(Kind::kCorridor, 0, d, per_row * w, d + c);
  for (int i = 0; i < per_row; ++i) {
    if (s.asymmetry && i == suite) {
      floor.add(Kind::kOffice, i * w, d + c, (i + 2) * w, 2 * d + c, 0.5 * (1.0 - fraction));
      ++i;
      continue;
    }
    // A half turn maps the south room at x to the north room at length − x: its door mirrored.
    floor.add(Kind::kOffice, i * w, d + c, (i + 1) * w, 2 * d + c, 1.0 - fraction);
  }
}

// Twin wings: a south wing of offices and a north wing that is the south one turned by a half
// turn. With the asymmetry, the south wing's last office is split in two.
void twinWings(const GeneratorSpec& s, Floor& floor, std::mt19937_64& rng) {
  const int per_wing = std::max(2, (roomsOr(s.rooms, 10) + 1) / 2);
  const double d = s.room_depth, c = s.corridor_width;
  std::vector<double> widths = floor.widths(per_wing * s.room_width);
  for (double& w : widths) w = mm(w);
  double length = 0.0;
  for (double w : widths) length += w;
  std::uniform_real_distribution<double> placement(0.2, 0.8);
  std::vector<double> fractions;
  for (std::size_t i = 0; i < widths.size(); ++i) {
    fractions.push_back(s.doors == "center" ? 0.5 : placement(rng));
  }
  double x = 0.0;
  for (std::size_t i = 0; i < widths.size(); ++i) {
    const bool split = s.asymmetry && i + 1 == widths.size();
    if (split) {
      const double half = mm(0.5 * widths[i]);
      floor.add(Kind::kOffice, x, 0, x + half, d, 0.5);
      floor.add(Kind::kOffice, x + half, 0, x + widths[i], d, 0.5);
    } else {
      floor.add(Kind::kOffice, x, 0, x + widths[i], d, fractions[i]);
    }
    // Its half-turned twin in the north wing.
    floor.add(Kind::kOffice, length - x - widths[i], d + c, length - x, 2 * d + c,
              1.0 - fractions[i]);
    x += widths[i];
  }
  floor.add(Kind::kCorridor, 0, d, length, d + c);
}

// The grid the spaces tile: cell (i, j) spans [xs[i], xs[i+1]] × [ys[j], ys[j+1]].
struct Grid {
  std::vector<double> xs, ys;
  std::vector<std::vector<int>> owner;  // [i][j]: index of the space, -1 outside

  int at(int i, int j) const {
    if (i < 0 || j < 0 || i >= int(owner.size()) || j >= int(owner[0].size())) return -1;
    return owner[i][j];
  }
};

Grid gridOf(const std::vector<Space>& spaces) {
  std::set<double> xs, ys;
  for (const Space& s : spaces) {
    xs.insert({s.x0, s.x1});
    ys.insert({s.y0, s.y1});
  }
  Grid g{{xs.begin(), xs.end()}, {ys.begin(), ys.end()}, {}};
  g.owner.assign(g.xs.size() - 1, std::vector<int>(g.ys.size() - 1, -1));
  for (int k = 0; k < int(spaces.size()); ++k) {
    const Space& s = spaces[k];
    for (std::size_t i = 0; i + 1 < g.xs.size(); ++i) {
      const double cx = 0.5 * (g.xs[i] + g.xs[i + 1]);
      if (cx < s.x0 || cx > s.x1) continue;
      for (std::size_t j = 0; j + 1 < g.ys.size(); ++j) {
        const double cy = 0.5 * (g.ys[j] + g.ys[j + 1]);
        if (cy >= s.y0 && cy <= s.y1) g.owner[i][j] = k;
      }
    }
  }
  return g;
}

struct Wall {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool outer = false;
  bool vertical() const { return x0 == x1; }
  double start() const { return vertical() ? y0 : x0; }
  double end() const { return vertical() ? y1 : x1; }
  double line() const { return vertical() ? x0 : y0; }
};

// Walls along every grid line where the owners on its two sides differ, one wall per unbroken run
// of one kind (outer: the outside on one side), so long walls run past T-junctions.
std::vector<Wall> wallsOf(const Grid& g) {
  std::vector<Wall> out;
  const int nx = int(g.xs.size()) - 1, ny = int(g.ys.size()) - 1;
  for (int vertical = 0; vertical < 2; ++vertical) {
    const int lines = vertical ? nx + 1 : ny + 1;
    const int cells = vertical ? ny : nx;
    const std::vector<double>& along = vertical ? g.ys : g.xs;
    const auto sides = [&](int l, int m) {
      return vertical ? std::make_pair(g.at(l - 1, m), g.at(l, m))
                      : std::make_pair(g.at(m, l - 1), g.at(m, l));
    };
    for (int l = 0; l < lines; ++l) {
      const double at = vertical ? g.xs[l] : g.ys[l];
      int k = 0;
      while (k < cells) {
        const auto [a, b] = sides(l, k);
        if (a == b) {
          ++k;
          continue;
        }
        const bool outer = a < 0 || b < 0;
        int end = k + 1;
        while (end < cells) {
          const auto [p, q] = sides(l, end);
          if (p == q || (p < 0 || q < 0) != outer) break;
          ++end;
        }
        out.push_back(vertical ? Wall{at, along[k], at, along[end], outer}
                               : Wall{along[k], at, along[end], at, outer});
        k = end;
      }
    }
  }
  return out;
}

// The stretch of a wall two touching spaces share, in metres from the wall's start.
struct Side {
  int wall = -1;
  double from = 0, to = 0;
  double length() const { return to - from; }
};

std::optional<Side> sharedSide(const Space& a, const Space& b, const std::vector<Wall>& walls) {
  struct Touch {
    bool vertical;
    double line, lo, hi;
  };
  std::vector<Touch> touches;
  if (a.x1 == b.x0 || a.x0 == b.x1) {
    touches.push_back(
        {true, a.x1 == b.x0 ? a.x1 : a.x0, std::max(a.y0, b.y0), std::min(a.y1, b.y1)});
  }
  if (a.y1 == b.y0 || a.y0 == b.y1) {
    touches.push_back(
        {false, a.y1 == b.y0 ? a.y1 : a.y0, std::max(a.x0, b.x0), std::min(a.x1, b.x1)});
  }
  for (const Touch& t : touches) {
    if (t.hi - t.lo < 1e-6) continue;
    for (int w = 0; w < int(walls.size()); ++w) {
      const Wall& wall = walls[w];
      if (wall.vertical() != t.vertical || wall.line() != t.line) continue;
      if (wall.start() <= t.lo + 1e-9 && wall.end() >= t.hi - 1e-9) {
        return Side{w, t.lo - wall.start(), t.hi - wall.start()};
      }
    }
  }
  return std::nullopt;
}

struct Door {
  int wall = -1;
  double offset = 0, width = 0.9;
  int a = -1, b = -1;  // the spaces it joins
  Eigen::Vector2d centre(const std::vector<Wall>& walls) const {
    const Wall& w = walls[wall];
    return w.vertical() ? Eigen::Vector2d(w.x0, w.y0 + offset)
                        : Eigen::Vector2d(w.x0 + offset, w.y0);
  }
};

// Spaces reached from space 0 through the doors not in `closed`.
std::vector<bool> reached(int spaces, const std::vector<Door>& doors,
                          const std::vector<bool>& closed) {
  std::vector<std::vector<int>> next(spaces);
  for (std::size_t d = 0; d < doors.size(); ++d) {
    if (!closed.empty() && closed[d]) continue;
    next[doors[d].a].push_back(doors[d].b);
    next[doors[d].b].push_back(doors[d].a);
  }
  std::vector<bool> seen(spaces, false);
  std::queue<int> open;
  open.push(0);
  seen[0] = true;
  while (!open.empty()) {
    const int s = open.front();
    open.pop();
    for (int t : next[s]) {
      if (!seen[t]) {
        seen[t] = true;
        open.push(t);
      }
    }
  }
  return seen;
}

// Whether spaces a and b are still joined through the doors not closed: a search from both ends
// at once, each step growing the smaller side, so a door that would cut off a few rooms is found
// out after visiting those few (closing doors in a building of thousands of rooms stays fast).
// `doors_of[k]` lists the doors of space k.
bool stillJoined(int a, int b, const std::vector<Door>& doors,
                 const std::vector<std::vector<int>>& doors_of, const std::vector<bool>& closed) {
  if (a == b) return true;
  std::vector<char> side(doors_of.size(), 0);  // 1: reached from a, 2: from b
  std::vector<int> frontier[2] = {{a}, {b}};
  side[std::size_t(a)] = 1;
  side[std::size_t(b)] = 2;
  while (!frontier[0].empty() && !frontier[1].empty()) {
    const int grow = frontier[0].size() <= frontier[1].size() ? 0 : 1;
    std::vector<int> next;
    for (int k : frontier[grow]) {
      for (int d : doors_of[std::size_t(k)]) {
        if (closed[std::size_t(d)]) continue;
        const int other =
            doors[std::size_t(d)].a == k ? doors[std::size_t(d)].b : doors[std::size_t(d)].a;
        if (side[std::size_t(other)] == grow + 1) continue;
        if (side[std::size_t(other)] != 0) return true;  // the two searches met
        side[std::size_t(other)] = char(grow + 1);
        next.push_back(other);
      }
    }
    frontier[grow] = std::move(next);
  }
  return false;
}

bool allTrue(const std::vector<bool>& v) {
  return std::all_of(v.begin(), v.end(), [](bool b) { return b; });
}

}  // namespace

const std::vector<std::string>& generatorFamilies() {
  static const std::vector<std::string> kFamilies = {
      "office", "l-shape", "t-shape", "u-shape", "hotel", "twin-wings", "hall", "site", "parking"};
  return kFamilies;
}

namespace {

// The spec's ranges (docs/sweeps.md): every value the generator promises to build.
void checkSpec(const GeneratorSpec& spec) {
  const auto& families = generatorFamilies();
  if (std::find(families.begin(), families.end(), spec.family) == families.end()) {
    throw std::invalid_argument("family: unknown family \"" + spec.family + "\"");
  }
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  const double t = spec.wall_thickness;
  require(t >= 0.05 && t <= 0.5, "wall thickness: must be in [0.05, 0.5] m");
  require(spec.rooms >= 0 && spec.rooms <= 5000, "rooms: must be in [0, 5000] (0: the family's)");
  require(spec.room_width >= 2.0 && spec.room_width <= 20.0, "room width: must be in [2, 20] m");
  require(spec.room_depth >= 3.0 && spec.room_depth <= 20.0, "room depth: must be in [3, 20] m");
  require(spec.corridor_width >= 1.2 && spec.corridor_width <= 6.0,
          "corridor width: must be in [1.2, 6] m (a robot and a door must fit)");
  // The free width between a corridor's walls is the corridor width less one wall thickness (half
  // of each wall stands in it); the robot needs 1 m of it (its 0.35 m clearance on each side, and
  // the joints between corridors at least an office door wide).
  require(spec.corridor_width - t >= 1.0 - 1e-9,
          "corridor width: must be at least 1 m more than the wall thickness (" +
              std::to_string(t).substr(0, 4) + " m): its free width is what the robot walks in");
  require(spec.size_spread >= 0.0 && spec.size_spread <= 0.4, "size spread: must be in [0, 0.4]");
  require(spec.doors == "center" || spec.doors == "random" || spec.doors == "corner",
          "doors: must be center, random or corner");
  require(spec.height >= 2.4 && spec.height <= 10.0, "height: must be in [2.4, 10] m");
  require(spec.carrier == "legged" || spec.carrier == "handheld",
          "carrier: must be legged or handheld");
  for (const auto& [value, name] :
       {std::pair{spec.connecting_doors, "connecting doors"},
        std::pair{spec.shifted_walls, "shifted walls"},
        std::pair{spec.rotated_walls, "rotated walls"},
        std::pair{spec.shortened_walls, "shortened walls"},
        std::pair{spec.missing_walls, "missing walls"}, std::pair{spec.extra_walls, "extra walls"},
        std::pair{spec.closed_doors, "closed doors"},
        std::pair{spec.missing_columns, "missing columns"},
        std::pair{spec.moved_columns, "moved columns"}}) {
    require(value >= 0.0 && value <= 1.0, std::string(name) + ": must be a share in [0, 1]");
  }
  require(spec.shift_min >= 0.0 && spec.shift_min <= spec.shift_max && spec.shift_max <= 1.0,
          "shift range: must satisfy 0 <= shift min <= shift max <= 1 m");
  require(spec.rotation_min_deg >= 0.0 && spec.rotation_min_deg <= spec.rotation_max_deg &&
              spec.rotation_max_deg <= 45.0,
          "rotation range: must satisfy 0 <= rotation min <= rotation max <= 45 degrees");
  require(spec.rotation_about == "named" || spec.rotation_about == "any",
          "rotation about: must be named or any");
  require(spec.clutter_per_room >= 0.0 && spec.clutter_per_room <= 4.0,
          "clutter per room: must be in [0, 4]");
  // Walls meeting at less than 50° make rooms whose acute corners the robot cannot turn in, and
  // corners the matcher does not seed from (docs/matching.md).
  require(std::abs(spec.shear_deg) <= 40.0, "shear: must be in [-40, 40] degrees");
  require(std::abs(spec.turn_deg) <= 180.0, "turn: must be in [-180, 180] degrees");
}

// The floor as the stages below build it up: its spaces (corridors and halls first), the walls
// between them, which spaces touch along which side, the doors and the halls' partitions.
struct Layout {
  std::vector<Space> spaces;
  std::vector<Wall> walls;
  std::vector<std::vector<std::pair<int, Side>>> touching;  // per space: (neighbour, side)
  std::vector<Door> doors;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> partitions;
  int size() const { return int(spaces.size()); }
};

// The family's spaces, their walls and which of them touch. Draws office widths from `rng`.
Layout layOut(const GeneratorSpec& s, std::mt19937_64& rng) {
  Floor floor(s, rng);
  if (s.family == "office") bandedFloor(s, floor, Kind::kCorridor, 24);
  if (s.family == "l-shape") armedFloor(s, floor, 'L');
  if (s.family == "t-shape") armedFloor(s, floor, 'T');
  if (s.family == "u-shape") armedFloor(s, floor, 'U');
  if (s.family == "hotel") hotel(s, floor, rng);
  if (s.family == "twin-wings") twinWings(s, floor, rng);
  if (s.family == "hall") bandedFloor(s, floor, Kind::kHall, 12);
  Layout layout;
  // Corridors and halls first: the search for reachable rooms starts from space 0.
  layout.spaces = floor.spaces;
  std::stable_partition(layout.spaces.begin(), layout.spaces.end(),
                        [](const Space& x) { return x.kind != Kind::kOffice; });
  layout.walls = wallsOf(gridOf(layout.spaces));
  const int n = layout.size();
  layout.touching.resize(n);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (auto side = sharedSide(layout.spaces[a], layout.spaces[b], layout.walls)) {
        layout.touching[a].push_back({b, *side});
        layout.touching[b].push_back({a, *side});
      }
    }
  }
  return layout;
}

// Doors: each office to the corridor or hall it shares most with, corridors to each other,
// suites between neighbouring offices, then a door for every office no corridor reaches. Every
// draw is made whether or not it is used, so that one setting does not shift the later draws.
void placeDoors(const GeneratorSpec& s, Layout& layout, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double t = s.wall_thickness;
  const double end_margin = 0.5 * t + 0.15;
  const std::vector<Space>& spaces = layout.spaces;
  const auto& touching = layout.touching;
  const int n = layout.size();
  const auto addDoor = [&](int a, int b, const Side& side, double fraction, double width,
                           double margin) {
    const double lo = side.from + margin + 0.5 * width;
    const double hi = side.to - margin - 0.5 * width;
    if (hi < lo) return false;
    layout.doors.push_back(
        {side.wall, std::clamp(side.from + fraction * side.length(), lo, hi), width, a, b});
    return true;
  };
  std::uniform_real_distribution<double> placement(0.2, 0.8);
  for (int a = 0; a < n; ++a) {
    if (spaces[a].kind == Kind::kOffice) {
      const std::pair<int, Side>* best = nullptr;
      for (const auto& candidate : touching[a]) {
        if (spaces[candidate.first].kind == Kind::kOffice) continue;
        if (best == nullptr || candidate.second.length() > best->second.length()) best = &candidate;
      }
      const double drawn = placement(rng);  // drawn for every office, so the rule does not shift
      const double corner = unit(rng) < 0.5 ? 0.1 : 0.9;  // the streams of later rooms
      if (best == nullptr) continue;
      double fraction = spaces[a].door_fraction;
      if (fraction < 0) fraction = s.doors == "center" ? 0.5 : s.doors == "corner" ? corner : drawn;
      addDoor(a, best->first, best->second, fraction, kOfficeDoorWidth, end_margin);
    } else {
      for (const auto& [b, side] : touching[a]) {
        if (b < a || spaces[b].kind == Kind::kOffice) continue;
        // Two corridors meet across the narrower one's width: the opening keeps clear of the
        // crossing walls' ends, and where that would leave it narrower than an office door (a
        // corridor under 1.4 m), it takes all of the free width between those walls, so the
        // robot passes wherever the corridor itself lets it.
        double width = std::min(2.0, side.length() - 2.0 * end_margin);
        double margin = end_margin;
        if (width < kOfficeDoorWidth) {
          margin = 0.5 * t + 0.02;
          width = side.length() - 2.0 * margin;
        }
        addDoor(a, b, side, 0.5, width, margin);
      }
    }
  }
  // Doors between neighbouring offices (suites), drawn for every pair so that the share does not
  // shift later draws.
  for (int a = 0; a < n; ++a) {
    for (const auto& [b, side] : touching[a]) {
      const bool draw = unit(rng) < s.connecting_doors;
      if (b > a && draw && spaces[a].kind == Kind::kOffice && spaces[b].kind == Kind::kOffice) {
        addDoor(a, b, side, 0.5, kOfficeDoorWidth, end_margin);
      }
    }
  }
  // Offices no corridor reaches get a door to a reached neighbour.
  for (bool grew = true; grew;) {
    grew = false;
    const std::vector<bool> seen = reached(n, layout.doors, {});
    for (int a = 0; a < n && !grew; ++a) {
      if (seen[a]) continue;
      for (const auto& [b, side] : touching[a]) {
        if (seen[b] && addDoor(a, b, side, 0.5, kOfficeDoorWidth, end_margin)) {
          grew = true;
          break;
        }
      }
    }
  }
  if (!allTrue(reached(n, layout.doors, {}))) {
    throw std::invalid_argument("rooms: these parameters leave a room without a door that fits");
  }
}

// The hall's partitions: free-standing walls clear of the hall's sides, of its doors and of
// each other. Only what is near the hall is checked: another hall's partitions are more than
// 4 m away (2 m clear of each side), a door farther than 2.5 m from the hall's box cannot come
// within 2.5 m of a partition inside it. A hall takes what fits: placing stops after
// kMaxMisses draws in a row that did not fit, so asking for more than fits costs little.
void placePartitions(const GeneratorSpec& s, Layout& layout, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int kMaxMisses = 1000;
  auto& partitions = layout.partitions;
  for (int h = 0; h < layout.size(); ++h) {
    if (layout.spaces[h].kind != Kind::kHall) continue;
    const Space& hs = layout.spaces[h];
    const double area = (hs.x1 - hs.x0) * (hs.y1 - hs.y0);
    const int wanted = s.partitions >= 0 ? s.partitions : int(area / 40.0);
    const std::size_t before = partitions.size();
    std::vector<Eigen::Vector2d> near_doors;
    for (const Door& d : layout.doors) {
      const Eigen::Vector2d c = d.centre(layout.walls);
      const double dx = std::max({hs.x0 - c.x(), 0.0, c.x() - hs.x1});
      const double dy = std::max({hs.y0 - c.y(), 0.0, c.y() - hs.y1});
      if (std::hypot(dx, dy) < 2.5) near_doors.push_back(c);
    }
    int misses = 0;
    for (long attempt = 0;
         attempt < 100L * wanted && int(partitions.size() - before) < wanted && misses < kMaxMisses;
         ++attempt) {
      ++misses;
      const bool along_x = unit(rng) < 0.5;
      const double length = mm(2.0 + 2.0 * unit(rng));
      const double clear = 2.0;
      const double span_x = hs.x1 - hs.x0 - 2 * clear - (along_x ? length : 0.0);
      const double span_y = hs.y1 - hs.y0 - 2 * clear - (along_x ? 0.0 : length);
      if (span_x <= 0 || span_y <= 0) continue;
      const Eigen::Vector2d p0(mm(hs.x0 + clear + span_x * unit(rng)),
                               mm(hs.y0 + clear + span_y * unit(rng)));
      const Eigen::Vector2d p1 =
          p0 + (along_x ? Eigen::Vector2d(length, 0) : Eigen::Vector2d(0, length));
      bool ok = true;
      for (std::size_t q = before; ok && q < partitions.size(); ++q) {
        const auto& [q0, q1] = partitions[q];
        ok = !crosses(p0, p1, q0, q1) && segmentDistance(p0, p1, q0, q1) >= 1.6;
      }
      for (std::size_t k = 0; ok && k < near_doors.size(); ++k) {
        ok = segmentDistance(p0, p1, near_doors[k], near_doors[k]) >= 2.5;
      }
      if (ok) {
        partitions.push_back({p0, p1});
        misses = 0;
      }
    }
  }
}

// The plan ("isg.plan"): walls W<n>, partitions P<n>, doors D<n>, rooms R<n> (offices), C<n>
// (corridors) and H<n> (halls). Returns each space's room id.
std::vector<std::string> writePlan(const GeneratorSpec& spec, const GeneratorSpec& s,
                                   const Layout& layout, GeneratedBuilding& out) {
  const double t = s.wall_thickness;
  const auto& walls = layout.walls;
  const auto& partitions = layout.partitions;
  const auto& doors = layout.doors;
  const int n = layout.size();
  bim::Level level;
  level.id = "L0";
  level.height = s.height;
  auto addWall = [&](std::string id, double x0, double y0, double x1, double y1, double thickness) {
    bim::Wall wall;
    wall.id = std::move(id);
    wall.start = {mm(x0), mm(y0)};
    wall.end = {mm(x1), mm(y1)};
    wall.thickness = thickness;
    wall.height = level.height;
    level.walls.push_back(std::move(wall));
  };
  for (std::size_t w = 0; w < walls.size(); ++w) {
    addWall("W" + std::to_string(w + 1), walls[w].x0, walls[w].y0, walls[w].x1, walls[w].y1, t);
  }
  for (std::size_t p = 0; p < partitions.size(); ++p) {
    addWall("P" + std::to_string(p + 1), partitions[p].first.x(), partitions[p].first.y(),
            partitions[p].second.x(), partitions[p].second.y(), 0.1);
  }
  for (std::size_t d = 0; d < doors.size(); ++d) {
    bim::Door door;
    door.id = "D" + std::to_string(d + 1);
    door.wall = "W" + std::to_string(doors[d].wall + 1);
    door.offset = mm(doors[d].offset);
    door.width = mm(doors[d].width);
    door.height = 2.1;
    door.rooms_inferred = true;  // the parser finds them from the outlines
    level.doors.push_back(std::move(door));
  }
  std::vector<std::string> ids(n);
  int offices = 0, corridors = 0, halls = 0;
  for (int k = 0; k < n; ++k) {
    const Space& sp = layout.spaces[k];
    bim::Room room;
    if (sp.kind == Kind::kOffice) {
      ids[k] = "R" + std::to_string(++offices);
      room.name = "Office " + std::to_string(offices);
    } else if (sp.kind == Kind::kCorridor) {
      ids[k] = "C" + std::to_string(++corridors);
      room.name = "Corridor " + std::to_string(corridors);
    } else {
      ids[k] = "H" + std::to_string(++halls);
      room.name = "Hall " + std::to_string(halls);
    }
    room.id = ids[k];
    const double h = 0.5 * t;
    room.outline = {{mm(sp.x0 + h), mm(sp.y0 + h)},
                    {mm(sp.x1 - h), mm(sp.y0 + h)},
                    {mm(sp.x1 - h), mm(sp.y1 - h)},
                    {mm(sp.x0 + h), mm(sp.y1 - h)}};
    level.rooms.push_back(std::move(room));
  }
  out.offices = offices;
  out.corridors = corridors + halls;
  char title[160];
  std::snprintf(title, sizeof title, "generated %s: %d offices, %d corridors or halls, seed %llu",
                spec.family.c_str(), offices, corridors + halls, (unsigned long long)spec.seed);
  bim::Plan plan;
  plan.name = title;
  plan.levels.push_back(std::move(level));
  // Written as people write plans: wall heights and door rooms left to the parser. The file's
  // keys come sorted (nlohmann::json), as generated plans always were.
  out.plan = json::parse(
      bim::planToJson(plan, {.every_wall_height = false, .inferred_door_rooms = false}).dump());
  return ids;
}

}  // namespace

json generatedAsBuiltJson(const bim::AsBuilt& as_built) {
  return json(bim::asBuiltToJson(as_built, {.empty_lists = false, .default_fields = false}));
}

namespace {

// Which of the layout's walls carry a door.
std::vector<bool> wallsWithDoors(const Layout& layout) {
  std::vector<bool> has_door(layout.walls.size(), false);
  for (const Door& d : layout.doors) has_door[d.wall] = true;
  return has_door;
}

// The walls the as-built changes drawn so far left unbuilt.
std::set<std::string> missingWallIds(const bim::AsBuilt& as_built) {
  return {as_built.missing_walls.begin(), as_built.missing_walls.end()};
}

// As built, walls: inner walls shifted, walls between two offices (no door) missing. Three draws
// a wall, whatever it is.
void drawWallChanges(const GeneratorSpec& s, const Layout& layout, std::mt19937_64& built_rng,
                     bim::AsBuilt& as_built) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto& walls = layout.walls;
  // Which spaces each wall bounds, and which walls carry doors.
  std::vector<std::set<int>> bounds(walls.size());
  for (int a = 0; a < layout.size(); ++a) {
    for (const auto& [b, side] : layout.touching[a]) bounds[side.wall].insert({a, b});
  }
  const std::vector<bool> has_door = wallsWithDoors(layout);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const bool between_offices = !walls[w].outer && !has_door[w] && !bounds[w].empty() &&
                                 std::all_of(bounds[w].begin(), bounds[w].end(), [&](int k) {
                                   return layout.spaces[k].kind == Kind::kOffice;
                                 });
    const double draw_missing = unit(built_rng), draw_shift = unit(built_rng);
    const double offset = (s.shift_min + (s.shift_max - s.shift_min) * unit(built_rng)) *
                          (unit(built_rng) < 0.5 ? -1 : 1);
    if (between_offices && draw_missing < s.missing_walls) {
      as_built.missing_walls.push_back("W" + std::to_string(w + 1));
    } else if (!walls[w].outer && draw_shift < s.shifted_walls) {
      as_built.wall_shifts.push_back({"W" + std::to_string(w + 1), mm(offset)});
    }
  }
}

// As built, turned walls: door-less inner walls not missing, each with probability
// rotated_walls, turned about its start, centre or end (or any point along it). The angle is capped
// so that no point of the wall swings more than 1.2 m (a third of an office): a long wall turns
// less.
void drawWallRotations(const GeneratorSpec& s, const Layout& layout, std::mt19937_64& turn_rng,
                       bim::AsBuilt& as_built) {
  if (s.rotated_walls <= 0.0) return;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<bool> has_door = wallsWithDoors(layout);
  const std::set<std::string> missing = missingWallIds(as_built);
  const bim::WallRotation::About abouts[] = {bim::WallRotation::About::kStart,
                                             bim::WallRotation::About::kCentre,
                                             bim::WallRotation::About::kEnd};
  for (std::size_t w = 0; w < layout.walls.size(); ++w) {
    const Wall& wall = layout.walls[w];
    const std::string id = "W" + std::to_string(w + 1);
    const double draw = unit(turn_rng), size = unit(turn_rng), sign = unit(turn_rng);
    const double about_draw = unit(turn_rng);
    const int about = std::min(2, int(3.0 * about_draw));
    if (wall.outer || has_door[w] || missing.count(id) || draw >= s.rotated_walls) continue;
    const double length = std::abs(wall.end() - wall.start());
    // About its start, centre or end, or (rotation_about "any") the point the same draw places
    // along it, in metres from its start: the farther end swings the most.
    const bool anywhere = s.rotation_about == "any";
    const double along = mm(about_draw * length);
    const double reach =
        anywhere ? std::max(along, length - along) : (about == 1 ? 0.5 * length : length);
    const double cap_deg = common::degrees(std::asin(std::min(1.0, 1.2 / std::max(reach, 1e-9))));
    const double angle =
        std::min(s.rotation_min_deg + (s.rotation_max_deg - s.rotation_min_deg) * size, cap_deg);
    bim::WallRotation turn;
    turn.wall = id;
    turn.angle_deg = std::round(angle * 10.0) / 10.0 * (sign < 0.5 ? -1 : 1);
    turn.about = anywhere ? bim::WallRotation::About::kAlong : abouts[about];
    if (anywhere) turn.along_m = along;
    as_built.wall_rotations.push_back(turn);
  }
}

// As built, walls built in part: door-less inner walls at least 2.5 m long, not missing, each
// with probability shortened_walls: a start or an end cut back, or a gap in the middle, of 0.8 m
// to half the wall, each part that stands at least 0.5 m. Four draws a wall, whatever it is.
void drawShortenedWalls(const GeneratorSpec& s, const Layout& layout, std::mt19937_64& cut_rng,
                        bim::AsBuilt& as_built) {
  if (s.shortened_walls <= 0.0) return;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<bool> has_door = wallsWithDoors(layout);
  const std::set<std::string> missing = missingWallIds(as_built);
  for (std::size_t w = 0; w < layout.walls.size(); ++w) {
    const Wall& wall = layout.walls[w];
    const std::string id = "W" + std::to_string(w + 1);
    const double draw = unit(cut_rng), kind = unit(cut_rng), size = unit(cut_rng),
                 where = unit(cut_rng);
    const double length = std::abs(mm(wall.end()) - mm(wall.start()));  // as the plan has it
    if (wall.outer || has_door[w] || missing.count(id) || length < 2.5 ||
        draw >= s.shortened_walls) {
      continue;
    }
    const double cut = mm(0.8 + (0.5 * length - 0.8) * size);
    // The end to the millimetre below the wall's length as the plan's rounded ends give it: a
    // part may not run past the wall.
    const double end = std::floor(length * 1000.0 - 1e-6) / 1000.0;
    bim::ShortenedWall shortened{id, {}};
    if (kind < 1.0 / 3.0) {
      shortened.built = {{cut, end}};
    } else if (kind < 2.0 / 3.0) {
      shortened.built = {{0.0, mm(length - cut)}};
    } else {
      const double from = mm(0.5 + (length - 1.0 - cut) * where);
      shortened.built = {{0.0, from}, {mm(from + cut), end}};
    }
    as_built.shortened_walls.push_back(std::move(shortened));
  }
}

// As built, doors: closed where closing keeps every space reached. Every space is reached through
// the open doors (placeDoors checked it); closing a door keeps it so exactly when its two sides
// stay joined without it.
void drawClosedDoors(const GeneratorSpec& s, const Layout& layout, std::mt19937_64& built_rng,
                     bim::AsBuilt& as_built) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto& doors = layout.doors;
  std::vector<std::vector<int>> doors_of(static_cast<std::size_t>(layout.size()));
  for (std::size_t d = 0; d < doors.size(); ++d) {
    doors_of[std::size_t(doors[d].a)].push_back(int(d));
    doors_of[std::size_t(doors[d].b)].push_back(int(d));
  }
  std::vector<bool> closed(doors.size(), false);
  for (std::size_t d = 0; d < doors.size(); ++d) {
    if (unit(built_rng) >= s.closed_doors) continue;
    closed[d] = true;
    if (stillJoined(doors[d].a, doors[d].b, doors, doors_of, closed)) {
      as_built.closed_doors.push_back("D" + std::to_string(d + 1));
    } else {
      closed[d] = false;  // would cut a room off
    }
  }
}

// An unplanned partition 0.1 m thick from `start` to `end` (to the millimetre), on the robot's
// level, as high as the level.
bim::ExtraWall extraWall(const Eigen::Vector2d& start, const Eigen::Vector2d& end) {
  bim::ExtraWall wall;
  wall.start = {mm(start.x()), mm(start.y())};
  wall.end = {mm(end.x()), mm(end.y())};
  wall.thickness = 0.1;
  return wall;
}

// As built, offices: clutter boxes in their corners, clear of the doors, and an unplanned
// partition. The draws of each corner are made whether or not a box is placed there.
void drawOfficeContents(const GeneratorSpec& s, const Layout& layout, std::mt19937_64& built_rng,
                        bim::AsBuilt& as_built) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double t = s.wall_thickness;
  const auto& walls = layout.walls;
  for (int k = 0; k < layout.size(); ++k) {
    const Space& sp = layout.spaces[k];
    if (sp.kind != Kind::kOffice) continue;
    const double h = 0.5 * t;
    const double ix0 = sp.x0 + h, ix1 = sp.x1 - h, iy0 = sp.y0 + h, iy1 = sp.y1 - h;
    std::vector<Eigen::Vector2d> door_centres;
    const Door* own = nullptr;
    for (const Door& d : layout.doors) {
      if (d.a == k || d.b == k) {
        door_centres.push_back(d.centre(walls));
        if (own == nullptr) own = &d;
      }
    }
    const int boxes =
        int(s.clutter_per_room) + (unit(built_rng) < s.clutter_per_room - int(s.clutter_per_room));
    std::vector<int> corners = {0, 1, 2, 3};
    std::shuffle(corners.begin(), corners.end(), built_rng);
    int placed = 0;
    for (int corner : corners) {
      const Eigen::Vector3d size(mm(0.4 + 0.6 * unit(built_rng)), mm(0.4 + 0.6 * unit(built_rng)),
                                 mm(0.5 + 0.7 * unit(built_rng)));
      const double yaw = mm(0.4 * unit(built_rng) - 0.2);
      if (placed >= boxes) continue;  // the draws above are made for every corner, placed or not
      if (ix1 - ix0 < size.x() + 2.0 || iy1 - iy0 < size.y() + 2.0) continue;
      const double inset = 0.25;
      const double cx = (corner & 1) ? ix1 - inset - 0.5 * size.x() : ix0 + inset + 0.5 * size.x();
      const double cy = (corner & 2) ? iy1 - inset - 0.5 * size.y() : iy0 + inset + 0.5 * size.y();
      bool clear = true;
      for (const auto& c : door_centres)
        clear = clear && (c - Eigen::Vector2d(cx, cy)).norm() >= 1.8;
      if (!clear) continue;
      bim::Clutter box;
      box.center = {mm(cx), mm(cy), mm(0.5 * size.z())};
      box.size = size;
      box.yaw = yaw;
      as_built.clutter.push_back(box);
      ++placed;
    }
    // An unplanned partition: parallel to the door's wall, 1 m before the far side, 40 % long.
    if (unit(built_rng) < s.extra_walls && own != nullptr) {
      const bool door_wall_vertical = walls[own->wall].vertical();
      const Eigen::Vector2d door = own->centre(walls);
      if (door_wall_vertical && ix1 - ix0 >= 3.0) {
        const double x = door.x() < 0.5 * (sp.x0 + sp.x1) ? ix1 - 1.0 : ix0 + 1.0;
        const double mid = 0.5 * (iy0 + iy1), half = 0.2 * (iy1 - iy0);
        as_built.extra_walls.push_back(extraWall({x, mid - half}, {x, mid + half}));
      } else if (!door_wall_vertical && iy1 - iy0 >= 3.0) {
        const double y = door.y() < 0.5 * (sp.y0 + sp.y1) ? iy1 - 1.0 : iy0 + 1.0;
        const double mid = 0.5 * (ix0 + ix1), half = 0.2 * (ix1 - ix0);
        as_built.extra_walls.push_back(extraWall({mid - half, y}, {mid + half, y}));
      }
    }
  }
}

// The building, before it is read as isg check reads it: the spec checked, the floor laid out,
// doors and partitions placed (the plan's stream), then what was built otherwise (the as-built
// stream) and where the robot starts. The stages draw in this order, always.
GeneratedBuilding generateFamily(const GeneratorSpec& spec) {
  checkSpec(spec);
  if (spec.family == "site") return generateSite(spec);
  if (spec.family == "parking") return generateParking(spec);
  // Separate streams for the plan and for the as-built changes, so that a denser clutter does
  // not move the walls.
  std::mt19937_64 rng(spec.seed * 0x9E3779B97F4A7C15ULL + 1);
  std::mt19937_64 built_rng(spec.seed * 0xD1B54A32D192ED03ULL + 7);

  GeneratorSpec s = spec;
  if (s.family == "hotel") s.size_spread = 0.0;
  // Suites drawn at random would break the half-turn symmetry these two families are about.
  if (s.family == "hotel" || s.family == "twin-wings") s.connecting_doors = 0.0;
  Layout layout = layOut(s, rng);
  placeDoors(s, layout, rng);
  placePartitions(s, layout, rng);

  GeneratedBuilding out;
  out.name = spec.family + "-" + std::to_string(spec.seed);
  const std::vector<std::string> ids = writePlan(spec, s, layout, out);

  bim::AsBuilt& as_built = out.as_built;
  drawWallChanges(s, layout, built_rng, as_built);
  std::mt19937_64 turn_rng(spec.seed * 0xA0761D6478BD642FULL + 11);
  drawWallRotations(s, layout, turn_rng, as_built);
  std::mt19937_64 cut_rng(spec.seed * 0xE7037ED1A0B428DBULL + 13);
  drawShortenedWalls(s, layout, cut_rng, as_built);
  drawClosedDoors(s, layout, built_rng, as_built);
  drawOfficeContents(s, layout, built_rng, as_built);
  // The robot starts in an office drawn from the seed and tours every room.
  std::vector<int> office_index;
  for (int k = 0; k < layout.size(); ++k) {
    if (layout.spaces[k].kind == Kind::kOffice) office_index.push_back(k);
  }
  const int start = office_index.empty() ? 0
                                         : office_index[std::uniform_int_distribution<std::size_t>(
                                               0, office_index.size() - 1)(built_rng)];
  out.scenario = {
      {"format", "isg.scenario"},
      {"version", 1},
      {"plan", out.name + ".json"},
      {"seed", spec.seed},
      {"robot", {{"level", "L0"}, {"start", {{"room", ids[start]}}}, {"route", "tour"}}}};
  leanBuilding(out.plan, as_built, s.shear_deg, s.turn_deg);
  out.scenario["as_built"] = generatedAsBuiltJson(as_built);
  return out;
}

// The family's building, carried as the spec says (legged, the scenario's default, is not
// written: a legged building is the same bytes as before the option was).
GeneratedBuilding generateUnchecked(const GeneratorSpec& spec) {
  GeneratedBuilding building = generateFamily(spec);
  if (spec.carrier != "legged") building.scenario["robot"]["carrier"] = spec.carrier;
  return building;
}

// Why the building's plan or scenario is refused, as isg check would refuse it (a plan limit:
// rooms, extent, clutter items ...); nullopt when both read without error or warning.
std::optional<std::string> refusal(const GeneratedBuilding& b) {
  try {
    common::Warnings warnings;
    const common::JsonSource plan_source{b.name + ".json", &warnings};
    bim::Plan plan = bim::parsePlan(common::JsonNode(b.plan, "", plan_source));
    const common::JsonSource scenario_source{b.name + ".asbuilt.json", &warnings};
    bim::parseScenario(common::JsonNode(b.scenario, "", scenario_source),
                       [&](const common::JsonNode&) {
                         return bim::LoadedPlan{plan, plan_source.file};
                       });
    if (!warnings.empty()) return warnings.front().str();
  } catch (const common::InputError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

}  // namespace

GeneratedBuilding generateBuilding(const GeneratorSpec& spec) {
  GeneratedBuilding building = generateUnchecked(spec);
  const std::optional<std::string> why = refusal(building);
  if (!why) return building;
  // Too many rooms for the plan's limits (its corridors count as rooms, a one-corridor floor
  // grows longer than a level may be): the largest count that works is found and said, so that
  // the message is a range the user can act on.
  const int asked = spec.rooms > 0 ? spec.rooms : 0;
  int good = 0;
  for (int lo = 1, hi = asked - 1; lo <= hi;) {
    GeneratorSpec fewer = spec;
    fewer.rooms = lo + (hi - lo) / 2;
    if (refusal(generateUnchecked(fewer))) {
      hi = fewer.rooms - 1;
    } else {
      good = fewer.rooms;
      lo = fewer.rooms + 1;
    }
  }
  if (good > 0) {
    throw std::invalid_argument(
        "rooms: " + std::to_string(asked) + " offices make a plan isg check refuses (" + *why +
        "); " + (std::string("aeiou").find(spec.family[0]) != std::string::npos ? "an " : "a ") +
        spec.family + " of these parameters holds at most " + std::to_string(good));
  }
  throw std::invalid_argument("family: the " + spec.family +
                              " of these parameters is refused by "
                              "isg check (" +
                              *why + ")");
}

}  // namespace isg::worlds
