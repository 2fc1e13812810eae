#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bim/scenario.hpp"

namespace isg::worlds {

// Procedural buildings (docs/sweeps.md, "Generated buildings"): a plan in the "isg.plan" v1
// format and an as-built scenario on it, both deterministic in the seed. Every building is a set
// of axis-aligned rectangles (offices, corridors, a hall) that tile its floor; walls run along
// the rectangles' shared sides and are merged into long walls where they line up, so faces meet
// in T-junctions as in real buildings. Each room gets a door to a corridor or hall it touches
// (or, failing that, to a neighbour already reachable), corridors meet through wide doorways,
// and every room is reachable from every other.

// The families on offer, in the order --help lists them.
const std::vector<std::string>& generatorFamilies();

struct GeneratorSpec {
  std::string family = "office";
  std::uint64_t seed = 1;
  int rooms = 0;              // target number of offices (corridors and halls not counted); 0: the
                              // family's default
  double room_width = 4.0;    // mean width of an office along its corridor, metres
  double room_depth = 5.0;    // depth of an office from its corridor, metres
  double size_spread = 0.25;  // relative spread of office widths (0: all alike); hotel: forced 0
  double corridor_width = 1.8;     // metres
  std::string doors = "random";    // where a room's door sits along its corridor side: center,
                                   // random (20–80 %), corner (near one end)
  double connecting_doors = 0.15;  // share of neighbouring offices with a door between them
                                   // (hotel, twin-wings: none, to keep their symmetry)
  bool asymmetry = true;           // twin-wings and hotel: one change that breaks the symmetry
  int partitions = -1;             // hall: free-standing partitions (-1: one per 40 m² of hall)
  double wall_thickness = 0.2;
  // Who carries the sensors on the tour: "legged" (the legged base, the scenario's default) or
  // "handheld" (a person walking; docs/simulation.md, "Carriers").
  std::string carrier = "legged";
  double height = 3.0;
  // As-built deviations, by density.
  double clutter_per_room = 1.0;  // mean clutter boxes per office
  double shifted_walls = 0.1;     // share of inner walls moved shift_min–shift_max metres
  double shift_min = 0.03;        // m, either way
  double shift_max = 0.08;
  // Share of door-less inner walls turned rotation_min_deg–rotation_max_deg (either way) about
  // their start, centre or end; drawn from a stream of their own, so that turning walls changes
  // no other draw.
  double rotated_walls = 0.0;
  double rotation_min_deg = 3.0;
  double rotation_max_deg = 15.0;
  // What a rotated wall turns about: "named" its start, centre or end; "any" a point drawn
  // anywhere along it (written as metres from its start).
  std::string rotation_about = "named";
  // Share of door-less inner walls at least 2.5 m long, not missing, built in part: a start or
  // an end cut back, or a gap in the middle, of 0.8 m to half the wall (each part left at least
  // 0.5 m); drawn from a stream of their own.
  double shortened_walls = 0.0;
  double missing_walls = 0.0;  // share of office–office walls without doors left unbuilt
  double extra_walls = 0.0;    // share of offices with an unplanned partition
  double closed_doors = 0.0;   // share of doors closed among those that can be (the rooms
                               // stay connected)
  // Site family: shares of the columns inside the façade left unbuilt, and moved 0.1–0.25 m in
  // a direction of their own; drawn from a stream of their own, after every other draw.
  double missing_columns = 0.0;
  double moved_columns = 0.0;
  // Non-Manhattan (worlds/plan_lean.hpp): the whole building sheared along x by shear_deg (the
  // walls across its corridors lean that far from square), then turned by turn_deg about B's
  // origin. Not the site family's.
  double shear_deg = 0.0;
  double turn_deg = 0.0;
};

struct GeneratedBuilding {
  std::string name;         // "<family>-<seed>"
  nlohmann::json plan;      // "isg.plan" v1
  nlohmann::json scenario;  // "isg.scenario" v1, "plan": "<name>.json", as-built deviations
  bim::AsBuilt as_built;    // the scenario's "as_built", which is written from it
  int offices = 0;
  int corridors = 0;
};

// A generated scenario's "as_built" as people write one (bim::asBuiltToJson: the lists that hold
// something, no field at its default), its keys sorted as generated files always had them.
nlohmann::json generatedAsBuiltJson(const bim::AsBuilt& as_built);

// The building of `spec`. Throws std::invalid_argument naming the parameter for a family it does
// not know or parameters that cannot make a building (e.g. a corridor too narrow for a door).
GeneratedBuilding generateBuilding(const GeneratorSpec& spec);

}  // namespace isg::worlds
