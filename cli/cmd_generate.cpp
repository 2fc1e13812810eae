#include "cli/cmd_generate.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "cli/progress_bar.hpp"
#include "common/atomic_folder.hpp"
#include "common/plural.hpp"
#include "run/interrupt.hpp"
#include "sim/simulation.hpp"

namespace isg::cli {

GenerateCommand::GenerateCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("generate", "Procedural buildings: plans and as-built scenarios");
  app_->footer(
      "Writes DIR/<family>-<seed>.json (the plan) and DIR/<family>-<seed>.asbuilt.json (a "
      "scenario on it: the building as built, a start office drawn from the seed, a tour of every "
      "room) for seeds SEED … SEED+COUNT-1 of each family; the same seed gives the same bytes. "
      "FAMILY given twice is generated once. "
      "Families: office (bands of offices on both sides of corridors, joined by a spine), l-shape, "
      "t-shape, u-shape (a band with one or two arms), hotel (identical rooms on one corridor; "
      "with the asymmetry, one suite of two rooms), twin-wings (a wing and its half-turned twin; "
      "with the asymmetry, one office split in two), hall (an open hall with free-standing "
      "partitions between two rows of offices), site (a construction site's open floor: a grid of "
      "columns, round inside on some sites, a façade of columns with walled and open bays, one "
      "corner often cut on a slant, a core of small rooms, free-standing partitions, no rooms in "
      "the plan; as built, façade walls not built yet, often a wall built only in part, and "
      "pallets; the robot tours the open floor), parking (an underground car park: a grid of "
      "identical columns, square or round, 7.5–8.5 m apart, retaining walls round it, a ramp's "
      "walls, a stair core and a lift core; as built, perimeter walls not built yet, parked "
      "vehicles and pallets; the robot tours the open floor); 'all' is every family. "
      "Every building is checked "
      "as isg check and isg run would check it (the plan and scenario parse with no warning, the "
      "MuJoCo world builds, the tour reaches every room) before DIR is written, all at once. "
      "docs/sweeps.md (\"Generated buildings\").\n\n"
      "Example: isg generate all -o buildings --count 8 --rooms 16 --clutter-per-room 1.5");
  app_->add_option("family", families_, "families to generate, or all")
      ->option_text("FAMILY...")
      ->required()
      ->check(CLI::IsMember([] {
        auto names = worlds::generatorFamilies();
        names.push_back("all");
        return names;
      }()));
  app_->add_option("-o,--output", output_, "DIR to create")->option_text("DIR")->required();
  app_->add_option("--count", count_, "buildings per family")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  app_->add_option("--seed", seed_, "seed of the first building; the next ones count up")
      ->check(seedNumber())
      ->capture_default_str();
  addLayoutOptions();
  addAsBuiltOptions();
  app_->add_flag("--no-verify", no_verify_,
                 "skip building each world and planning its tour (large batches, trusted "
                 "parameters); plans and scenarios are still checked as isg check checks them");
  app_->add_flag("--force", force_, "replace DIR if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
}

// The building as planned: its offices, corridors, doors, walls and storey.
void GenerateCommand::addLayoutOptions() {
  app_->add_option("--rooms", spec_.rooms,
                   "offices per building, up to 5000 where the plan's limits allow: corridors are "
                   "rooms too (5000 a level) and a level is at most 1 km long (a hotel is one "
                   "corridor: about 430 rooms of 4 m); beyond, the message says how many fit")
      ->default_str("the family's: office, l/t/u-shape 24, hotel 22, twin-wings 10, hall 12");
  app_->add_option("--room-width", spec_.room_width, "mean office width along its corridor [m]")
      ->capture_default_str();
  app_->add_option("--room-depth", spec_.room_depth, "office depth from its corridor [m]")
      ->capture_default_str();
  app_->add_option("--size-spread", spec_.size_spread,
                   "relative spread of office widths, 0 … 0.4 (hotel: always 0)")
      ->capture_default_str();
  app_->add_option("--corridor-width", spec_.corridor_width, "corridor width [m]")
      ->capture_default_str();
  app_->add_option("--doors", spec_.doors,
                   "where an office's door sits on its corridor side: center, random (20–80 %), "
                   "corner")
      ->check(CLI::IsMember({"center", "random", "corner"}))
      ->capture_default_str();
  app_->add_option("--connecting-doors", spec_.connecting_doors,
                   "share of neighbouring offices with a door between them (what a closed door "
                   "can shut without cutting a room off)")
      ->capture_default_str();
  app_->add_flag("--symmetric", symmetric_,
                 "hotel and twin-wings without their one asymmetry: no route can tell the halves "
                 "apart");
  app_->add_option("--partitions", spec_.partitions,
                   "partitions in a hall, at most (a hall takes those that fit)")
      ->default_str("one per 40 m² of hall");
  app_->add_option("--wall-thickness", spec_.wall_thickness, "[m]")->capture_default_str();
  app_->add_option("--height", spec_.height, "storey height [m]")->capture_default_str();
  app_->add_option("--carrier", spec_.carrier,
                   "who carries the sensors on the tour: legged (the legged base) or handheld (a "
                   "person walking; written as the scenario's robot.carrier)")
      ->check(CLI::IsMember({"legged", "handheld"}))
      ->capture_default_str();
}

// The building as built (what differs from its plan), and the lean that makes it non-Manhattan.
void GenerateCommand::addAsBuiltOptions() {
  app_->add_option(
          "--clutter-per-room", spec_.clutter_per_room,
          "as built: mean clutter boxes per office, 0 … 4 (in its corners, clear of doors)")
      ->capture_default_str();
  app_->add_option("--shifted-walls", spec_.shifted_walls,
                   "as built: share of inner walls moved --shift-min to --shift-max metres")
      ->capture_default_str();
  app_->add_option("--shift-min", spec_.shift_min, "as built: smallest shift of a wall [m]")
      ->capture_default_str();
  app_->add_option("--shift-max", spec_.shift_max, "as built: largest shift of a wall [m]")
      ->capture_default_str();
  app_->add_option("--rotated-walls", spec_.rotated_walls,
                   "as built: share of door-less inner walls turned about their start, centre or "
                   "end (no point swung more than 1.2 m)")
      ->capture_default_str();
  app_->add_option("--rotation-min", spec_.rotation_min_deg,
                   "as built: smallest turn of a rotated wall [degrees]")
      ->capture_default_str();
  app_->add_option("--rotation-max", spec_.rotation_max_deg,
                   "as built: largest turn of a rotated wall [degrees]")
      ->capture_default_str();
  app_->add_option("--rotation-about", spec_.rotation_about,
                   "as built: what a rotated wall turns about: named (its start, centre or end) "
                   "or any (a point anywhere along it, written in metres from its start)")
      ->check(CLI::IsMember({"named", "any"}))
      ->capture_default_str();
  app_->add_option("--shortened-walls", spec_.shortened_walls,
                   "as built: share of door-less inner walls (2.5 m or longer) built in part: a "
                   "start or end cut back or a middle gap, 0.8 m to half the wall")
      ->capture_default_str();
  app_->add_option("--missing-columns", spec_.missing_columns,
                   "as built, site and parking families: share of the columns inside the façade "
                   "(the perimeter) not built yet")
      ->capture_default_str();
  app_->add_option("--moved-columns", spec_.moved_columns,
                   "as built, site and parking families: share of the columns inside the façade "
                   "(the perimeter) built 0.1–0.25 m off their planned centre")
      ->capture_default_str();
  app_->add_option("--shear", spec_.shear_deg,
                   "non-Manhattan: the building sheared along x so that the walls across its "
                   "corridors lean DEG from square and its rooms are parallelograms, -40 … 40 "
                   "[degrees]; not the site and parking families'")
      ->capture_default_str();
  app_->add_option("--turn", spec_.turn_deg,
                   "the whole building turned about B's origin, -180 … 180 [degrees] (after "
                   "--shear); not the site and parking families'")
      ->capture_default_str();
  app_->add_option("--missing-walls", spec_.missing_walls,
                   "as built: share of door-less walls between offices left unbuilt")
      ->capture_default_str();
  app_->add_option("--extra-walls", spec_.extra_walls,
                   "as built: share of offices with an unplanned partition")
      ->capture_default_str();
  app_->add_option("--closed-doors", spec_.closed_doors,
                   "as built: share of doors closed, among those whose closing cuts no room off")
      ->capture_default_str();
}

// Each family once ("hall hall" is one family: its buildings would have the same names).
std::vector<std::string> GenerateCommand::familiesAsked() const {
  std::vector<std::string> families;
  const auto add = [&](const std::string& family) {
    if (std::find(families.begin(), families.end(), family) == families.end()) {
      families.push_back(family);
    }
  };
  for (const auto& f : families_) {
    if (f == "all") {
      for (const auto& g : worlds::generatorFamilies()) add(g);
    } else {
      add(f);
    }
  }
  return families;
}

void GenerateCommand::warnOfOptionsThatDoNotApply(const std::vector<std::string>& families) const {
  // A site or a car park is drawn from its seed alone (docs/sweeps.md): an office parameter given
  // for one is said, not silently dropped.
  for (const char* grid_family : {"site", "parking"}) {
    if (std::find(families.begin(), families.end(), grid_family) == families.end()) continue;
    for (const char* option : {"--rooms",
                               "--room-width",
                               "--room-depth",
                               "--size-spread",
                               "--corridor-width",
                               "--doors",
                               "--connecting-doors",
                               "--symmetric",
                               "--partitions",
                               "--wall-thickness",
                               "--clutter-per-room",
                               "--shifted-walls",
                               "--shift-min",
                               "--shift-max",
                               "--rotated-walls",
                               "--rotation-min",
                               "--rotation-max",
                               "--rotation-about",
                               "--shortened-walls",
                               "--missing-walls",
                               "--extra-walls",
                               "--closed-doors",
                               "--shear",
                               "--turn"}) {
      if (app_->count(option) == 0) continue;
      std::fprintf(stderr,
                   "isg generate: warning: %s does not apply to the %s family (it takes its "
                   "seed, --count, --height, --carrier, --missing-columns and --moved-columns "
                   "only); its buildings are made without it\n",
                   option, grid_family);
    }
  }
  // Columns as built are the column-grid families': said for the others.
  for (const auto& family : families) {
    if (family == "site" || family == "parking") continue;
    for (const char* option : {"--missing-columns", "--moved-columns"}) {
      if (app_->count(option) == 0) continue;
      std::fprintf(stderr,
                   "isg generate: warning: %s applies to the site and parking families only "
                   "(the other families' plans have no columns); %s buildings are made without "
                   "it\n",
                   option, family.c_str());
    }
  }
}

// Bad parameters fail before anything is written, naming the option.
std::vector<worlds::GeneratedBuilding> GenerateCommand::makeBuildings(
    const std::vector<std::string>& families) const {
  std::vector<worlds::GeneratedBuilding> buildings;
  for (const auto& family : families) {
    for (int i = 0; i < count_; ++i) {
      worlds::GeneratorSpec spec = spec_;
      spec.family = family;
      spec.seed = seed_ + std::uint64_t(i);
      run::throwIfInterrupted();
      try {
        buildings.push_back(worlds::generateBuilding(spec));
      } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        const auto colon = what.find(':');
        std::string option = "--" + what.substr(0, colon);
        for (char& c : option) c = c == ' ' ? '-' : c;
        throw common::InputError(
            option, "",
            what.substr(colon + 2) + " (" + family + ", seed " + std::to_string(spec.seed) + ")");
      }
    }
  }
  return buildings;
}

void GenerateCommand::writeAndCheck(const worlds::GeneratedBuilding& b,
                                    const std::filesystem::path& dir) const {
  common::writeFile(dir / (b.name + ".json"), b.plan.dump(2) + "\n");
  const std::string scenario_path = (dir / (b.name + ".asbuilt.json")).string();
  common::writeFile(scenario_path, b.scenario.dump(2) + "\n");
  if (no_verify_) return;
  // As isg check and isg run would read it: a warning is a generator bug too.
  common::Warnings warnings;
  const bim::Scenario scenario = bim::loadScenario(scenario_path, &warnings);
  if (!warnings.empty()) {
    throw std::logic_error("generated " + b.name +
                           " reads with a warning: " + warnings.front().str());
  }
  const sim::Simulation simulation(scenario);
  // Never written: a building the robot cannot tour would give a table number for part of it.
  // Bad input for the parameters that made it, naming the rooms (or levels).
  if (const std::string part = sim::unreachedPart(simulation.route()); !part.empty()) {
    throw common::InputError(b.name, "",
                             "the tour cannot reach " + part + " of the generated building" +
                                 sim::coarseCellsNote(simulation.route()) +
                                 "; nothing was written: change the generator's parameters");
  }
}

int GenerateCommand::run() {
  const std::vector<std::string> families = familiesAsked();
  if (seed_ > std::numeric_limits<std::uint64_t>::max() - std::uint64_t(count_ - 1)) {
    throw common::InputError("--seed", "",
                             "seeds " + std::to_string(seed_) + " and the " +
                                 std::to_string(count_ - 1) + " after it pass 2^64 - 1");
  }
  // The output rule before any work: not the working directory, nor an earlier folder of
  // anything but generated buildings.
  common::checkCanCreateFolder(output_, common::OutputKind::kBuildings, force_);
  spec_.asymmetry = !symmetric_;
  warnOfOptionsThatDoNotApply(families);
  const std::vector<worlds::GeneratedBuilding> buildings = makeBuildings(families);
  ProgressBar bar("isg generate", quiet_);
  std::size_t offices = 0, largest = 0;
  common::writeFolderAtomically(output_, common::OutputKind::kBuildings, force_,
                                [&](const std::filesystem::path& dir) {
                                  for (std::size_t k = 0; k < buildings.size(); ++k) {
                                    const auto& b = buildings[k];
                                    offices += std::size_t(b.offices);
                                    largest = std::max(largest, std::size_t(b.offices));
                                    bar.update(double(k + 1) / double(buildings.size()), b.name);
                                    writeAndCheck(b, dir);
                                  }
                                  // The last building's checks may have taken a while: an interrupt
                                  // then still means nothing is written.
                                  run::throwIfInterrupted();
                                });
  bar.finish();
  std::printf("isg generate: wrote %s: %s (%s and %s), %s in all, up to %zu in one%s\n",
              output_.c_str(), common::counted(buildings.size(), "building").c_str(),
              common::counted(buildings.size(), "plan").c_str(),
              common::counted(buildings.size(), "as-built scenario").c_str(),
              common::counted(offices, "office").c_str(), largest,
              no_verify_ ? "" : "; each parsed, built and toured");
  return kExitOk;
}

}  // namespace isg::cli
