#include "sweep/suite.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

#include "common/json_reader.hpp"
#include "common/version.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sweep {

namespace {

namespace fs = std::filesystem;

// A generator parameter of the suite: the JSON name is the command line's without the dashes.
worlds::GeneratorSpec generatorSpec(const common::JsonNode& node) {
  node.expectObject({"family",
                     "seed",
                     "count",
                     "rooms",
                     "room_width",
                     "room_depth",
                     "size_spread",
                     "corridor_width",
                     "doors",
                     "symmetric",
                     "partitions",
                     "wall_thickness",
                     "height",
                     "clutter_per_room",
                     "shifted_walls",
                     "shift_min",
                     "shift_max",
                     "rotated_walls",
                     "rotation_min_deg",
                     "rotation_max_deg",
                     "rotation_about",
                     "shortened_walls",
                     "missing_walls",
                     "extra_walls",
                     "closed_doors",
                     "connecting_doors",
                     "missing_columns",
                     "moved_columns",
                     "shear_deg",
                     "turn_deg",
                     "carrier"});
  worlds::GeneratorSpec spec;
  spec.family = node.field("family").identifier();
  const auto& families = worlds::generatorFamilies();
  if (std::find(families.begin(), families.end(), spec.family) == families.end()) {
    std::string list;
    for (const auto& f : families) list += (list.empty() ? "" : ", ") + f;
    node.field("family").fail("unknown family " + common::inQuotes(spec.family) + " (one of " +
                              list + ")");
  }
  const auto number = [&](const char* key, double& into) {
    if (auto v = node.optionalField(key)) into = v->number();
  };
  if (auto v = node.optionalField("seed")) spec.seed = v->unsignedInteger();
  const auto integer = [&](const char* key, int& into, std::uint64_t most) {
    if (auto v = node.optionalField(key)) {
      const std::uint64_t value = v->unsignedInteger();
      if (value > most) v->fail("must be at most " + std::to_string(most));
      into = int(value);
    }
  };
  integer("rooms", spec.rooms, 5000);
  integer("partitions", spec.partitions, 10000);
  if (auto v = node.optionalField("doors")) spec.doors = v->string();
  if (auto v = node.optionalField("symmetric")) spec.asymmetry = !v->boolean();
  number("room_width", spec.room_width);
  number("room_depth", spec.room_depth);
  number("size_spread", spec.size_spread);
  number("corridor_width", spec.corridor_width);
  number("wall_thickness", spec.wall_thickness);
  number("height", spec.height);
  number("clutter_per_room", spec.clutter_per_room);
  number("shifted_walls", spec.shifted_walls);
  number("shift_min", spec.shift_min);
  number("shift_max", spec.shift_max);
  number("rotated_walls", spec.rotated_walls);
  number("rotation_min_deg", spec.rotation_min_deg);
  number("rotation_max_deg", spec.rotation_max_deg);
  if (auto v = node.optionalField("rotation_about")) spec.rotation_about = v->string();
  if (auto v = node.optionalField("carrier")) spec.carrier = v->string();
  number("shortened_walls", spec.shortened_walls);
  number("missing_walls", spec.missing_walls);
  number("extra_walls", spec.extra_walls);
  number("closed_doors", spec.closed_doors);
  number("connecting_doors", spec.connecting_doors);
  number("missing_columns", spec.missing_columns);
  number("moved_columns", spec.moved_columns);
  number("shear_deg", spec.shear_deg);
  number("turn_deg", spec.turn_deg);
  // The generator's own checks, reported at this node.
  try {
    (void)worlds::generateBuilding(spec);
  } catch (const std::invalid_argument& e) {
    node.fail(e.what());
  }
  return spec;
}

}  // namespace

Suite loadSuite(const std::string& path, const run::LocalizerRegistry& methods) {
  const nlohmann::json document = common::readJsonFile(path);
  const common::JsonSource source{path, nullptr};
  return parseSuite(common::JsonNode(document, "", source), path, methods);
}

namespace {

// A world added to the suite: its name must be free, not a file of the sweep's, and the worlds
// within the most cells of a sweep.
void addWorld(Suite& suite, std::set<std::string>& names, const common::JsonNode& at,
              SuiteWorld world) {
  // A world's name is the first folder of its run folders in SWEEP_DIR: "." and ".." would put
  // them beside or outside the sweep, the names of the sweep's own files would collide.
  const bool reserved = world.name == "." || world.name == ".." ||
                        std::find(kSweepFolderFiles.begin(), kSweepFolderFiles.end(), world.name) !=
                            kSweepFolderFiles.end();
  if (reserved) {
    at.fail("a world named " + common::inQuotes(world.name) +
            " (its file's name without .json) cannot name a folder of the sweep: rename "
            "the file");
  }
  if (!names.insert(world.name).second) {
    at.fail("a second world named " + common::inQuotes(world.name) +
            " (world names are the table's rows and folder names)");
  }
  if (suite.worlds.size() >= kMaxSweepCells) {
    at.fail("more than " + std::to_string(kMaxSweepCells) + " worlds (the most cells of a sweep)");
  }
  suite.worlds.push_back(std::move(world));
}

// A world named by a string: a built-in world, or a plan or scenario file relative to the
// suite's folder `base`.
SuiteWorld namedWorld(const common::JsonNode& entry, const fs::path& base) {
  // text(): a world's name becomes a folder name and a table row, and sweep.json must read
  // back what it was written with, so control characters are refused here.
  const std::string input = entry.text();
  if (input.empty()) entry.fail("must not be empty");
  SuiteWorld world;
  world.name = worlds::worldName(input);
  if (worlds::isBuiltin(input)) {
    // Checked now, not when its cells run: a misspelt built-in would fail every one of them.
    if (!worlds::builtinText(world.name)) {
      std::string list;
      for (const auto& n : worlds::builtinNames()) list += (list.empty() ? "" : ", ") + n;
      entry.fail("no built-in world " + common::inQuotes(world.name) + " (one of " + list + ")");
    }
    world.input = input;
    return world;
  }
  const fs::path file = fs::path(input).is_absolute() ? fs::path(input) : base / input;
  if (!fs::is_regular_file(file)) entry.fail("no such plan or scenario file: " + file.string());
  world.input = fs::weakly_canonical(file).string();
  return world;
}

void parseWorlds(const common::JsonNode& root, const std::string& path, Suite& suite) {
  const fs::path base = fs::absolute(fs::path(path)).parent_path();
  std::set<std::string> names;
  for (const auto& entry : root.field("worlds").elements(1, 100000, "worlds")) {
    if (entry.isString()) {
      addWorld(suite, names, entry, namedWorld(entry, base));
      continue;
    }
    entry.expectObject({"generate"});
    const common::JsonNode spec_node = entry.field("generate");
    const worlds::GeneratorSpec first = generatorSpec(spec_node);
    const std::uint64_t count =
        spec_node.has("count") ? spec_node.field("count").unsignedInteger() : 1;
    if (count < 1 || count > 10000) spec_node.field("count").fail("must be in [1, 10000]");
    for (std::uint64_t i = 0; i < count; ++i) {
      worlds::GeneratorSpec spec = first;
      spec.seed = first.seed + i;
      SuiteWorld world;
      world.name = spec.family + "-" + std::to_string(spec.seed);
      world.input = "worlds/" + world.name + ".asbuilt.json";
      world.generate = spec;
      addWorld(suite, names, spec_node, world);
    }
  }
}

void parseSeedsAndMethods(const common::JsonNode& root, const run::LocalizerRegistry& methods,
                          Suite& suite) {
  std::set<std::uint64_t> seen_seeds;
  for (const auto& s : root.field("seeds").elements(1, 100000, "seeds")) {
    const std::uint64_t seed = s.unsignedInteger();
    if (!seen_seeds.insert(seed).second) s.fail("seed " + std::to_string(seed) + " twice");
    suite.seeds.push_back(seed);
  }
  for (const auto& m : root.field("methods").elements(1, 100, "methods")) {
    const std::string name = m.nonEmptyString();
    if (methods.find(name) == nullptr) {
      std::string list;
      for (const auto& n : methods.names()) list += (list.empty() ? "" : ", ") + n;
      m.fail("unknown method " + common::inQuotes(name) + " (one of " + list + ")");
    }
    const std::string canonical = methods.canonical(name);
    if (std::find(suite.methods.begin(), suite.methods.end(), canonical) != suite.methods.end()) {
      m.fail("method " + common::inQuotes(canonical) + " twice");
    }
    suite.methods.push_back(canonical);
  }
  const std::uint64_t cells =
      std::uint64_t(suite.worlds.size()) * suite.methods.size() * suite.seeds.size();
  if (cells > kMaxSweepCells) {
    root.fail(std::to_string(cells) + " cells (" + std::to_string(suite.worlds.size()) +
              " worlds × " + std::to_string(suite.methods.size()) + " methods × " +
              std::to_string(suite.seeds.size()) + " seeds); a sweep holds at most " +
              std::to_string(kMaxSweepCells) + ": split the suite");
  }
}

// run.method_options: method → {KEY: VALUE}, each method's own check made here rather than in
// each cell's run.
void parseMethodOptions(const common::JsonNode& options, const run::LocalizerRegistry& methods,
                        Suite& suite) {
  if (!options.isObject()) options.fail("expected an object: method → {KEY: VALUE}");
  for (const auto& [method, settings] : options.raw().items()) {
    const common::JsonNode node = options.field(method);
    if (methods.find(method) == nullptr) node.fail("unknown method " + common::inQuotes(method));
    if (!settings.is_object()) node.fail("expected an object {KEY: VALUE}");
    auto& given = suite.method_options[methods.canonical(method)];
    for (const auto& [key, value] : settings.items()) {
      const common::JsonNode v = node.field(key);
      std::string text;
      if (value.is_string()) {
        text = v.string();
      } else if (value.is_number()) {
        text = value.dump();
      } else {
        v.fail("expected a number or a string");
      }
      given[key] = text;
    }
    try {
      methods.checkOptions(method, given);
    } catch (const std::invalid_argument& e) {
      node.fail(e.what());
    }
  }
}

void parseSlurm(const common::JsonNode& slurm, Suite& suite) {
  slurm.expectObject({"cpus_per_task", "time", "mem", "partition", "max_array_size", "options"});
  if (auto c = slurm.optionalField("cpus_per_task")) {
    suite.slurm.cpus_per_task = int(c->numberInRange(1, 1024));
  }
  if (auto t = slurm.optionalField("time")) suite.slurm.time = t->identifier();
  if (auto m = slurm.optionalField("mem")) suite.slurm.mem = m->identifier();
  if (auto p = slurm.optionalField("partition")) suite.slurm.partition = p->identifier();
  if (auto m = slurm.optionalField("max_array_size")) {
    const std::uint64_t most = m->unsignedInteger();
    if (most < 1 || most > 100000000) m->fail("must be in [1, 100000000]");
    suite.slurm.max_array_size = std::size_t(most);
  }
  if (auto o = slurm.optionalField("options")) {
    for (const auto& option : o->elements(0, 100, "options")) {
      suite.slurm.options.push_back(option.identifier());
    }
  }
}

}  // namespace

Suite parseSuite(const common::JsonNode& root, const std::string& path,
                 const run::LocalizerRegistry& methods) {
  root.expectObject(
      {"$schema", "format", "version", "name", "worlds", "seeds", "methods", "run", "slurm"});
  common::checkFormatAndVersion(root, kSuiteFormat, kSuiteVersion);
  Suite suite;
  suite.file = path;
  suite.name = root.has("name") ? root.field("name").text() : fs::path(path).stem().string();
  parseWorlds(root, path, suite);
  parseSeedsAndMethods(root, methods, suite);
  if (auto run = root.optionalField("run")) {
    run->expectObject({"duration", "threads", "start_pose", "method_options"});
    if (auto d = run->optionalField("duration")) suite.duration = d->positiveNumber();
    // A pose in numbers would be one building's: across a suite's worlds only the truth's is.
    if (auto p = run->optionalField("start_pose")) {
      if (p->string() != "truth") {
        p->fail("must be \"truth\" (isg run --start-pose truth: each world's own first pose)");
      }
      suite.start_pose_truth = true;
    }
    if (auto t = run->optionalField("threads")) suite.threads = int(t->numberInRange(1, 64));
    if (auto options = run->optionalField("method_options")) {
      parseMethodOptions(*options, methods, suite);
    }
  }
  // Each method's options as its runs will use them (checked above where given).
  for (const auto& method : suite.methods) {
    const auto given = suite.method_options.find(method);
    suite.effective_options[method] = methods.checkOptions(
        method,
        given == suite.method_options.end() ? std::map<std::string, std::string>{} : given->second);
  }
  if (auto slurm = root.optionalField("slurm")) parseSlurm(*slurm, suite);
  return suite;
}

std::vector<SweepCell> sweepCells(const Suite& suite) {
  std::vector<SweepCell> cells;
  for (const auto& world : suite.worlds) {
    for (const auto& method : suite.methods) {
      for (const std::uint64_t seed : suite.seeds) {
        SweepCell cell{world.name, method,
                       seed,       world.name + "/" + method + "/seed-" + std::to_string(seed),
                       {},         world.hash};
        cell.arguments = {"run",       world.input,
                          "--method",  method,
                          "--seed",    std::to_string(seed),
                          "-o",        cell.dir,
                          "--threads", std::to_string(suite.threads),
                          "-q"};
        if (suite.start_pose_truth) {
          cell.arguments.push_back("--start-pose");
          cell.arguments.push_back("truth");
        }
        if (suite.duration) {
          cell.arguments.push_back("--duration");
          cell.arguments.push_back(common::formatNumber(*suite.duration));
        }
        if (const auto it = suite.method_options.find(method); it != suite.method_options.end()) {
          for (const auto& [key, value] : it->second) {
            cell.arguments.push_back("--method-option");
            cell.arguments.push_back(key + "=" + value);
          }
        }
        cells.push_back(std::move(cell));
      }
    }
  }
  return cells;
}

std::string sweepPlanJson(const Suite& suite, const std::vector<SweepCell>& cells) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& c : cells) {
    list.push_back({{"world", c.world},
                    {"method", c.method},
                    {"seed", c.seed},
                    {"dir", c.dir},
                    {"arguments", c.arguments}});
  }
  nlohmann::json worlds = nlohmann::json::array();
  for (const auto& w : suite.worlds) {
    nlohmann::json entry = {{"name", w.name}, {"input", w.input}, {"hash", w.hash}};
    if (w.generate) entry["generate"] = generatorSpecJson(*w.generate);
    worlds.push_back(entry);
  }
  // What made the sweep's runs besides the worlds: each method's options as its runs use them,
  // and the build of isg that started the sweep (its cells run the same program).
  nlohmann::json options = nlohmann::json::object();
  for (const auto& [method, values] : suite.effective_options) {
    options[method] = nlohmann::json::object();
    for (const auto& [key, value] : values) options[method][key] = value;
  }
  const nlohmann::json plan = {{"format", "isg.sweep"},
                               {"version", 1},
                               {"name", suite.name},
                               {"suite", fs::absolute(suite.file).string()},
                               {"build_version", common::buildVersion()},
                               {"method_options", options},
                               {"worlds", worlds},
                               {"cells", list}};
  return plan.dump(1) + "\n";
}

nlohmann::json generatorSpecJson(const worlds::GeneratorSpec& s) {
  nlohmann::json j = {{"family", s.family},
                      {"seed", s.seed},
                      {"rooms", s.rooms},
                      {"room_width", s.room_width},
                      {"room_depth", s.room_depth},
                      {"size_spread", s.size_spread},
                      {"corridor_width", s.corridor_width},
                      {"doors", s.doors},
                      {"connecting_doors", s.connecting_doors},
                      {"symmetric", !s.asymmetry},
                      {"partitions", s.partitions},
                      {"wall_thickness", s.wall_thickness},
                      {"height", s.height},
                      {"clutter_per_room", s.clutter_per_room},
                      {"shifted_walls", s.shifted_walls},
                      {"shift_min", s.shift_min},
                      {"shift_max", s.shift_max},
                      {"rotated_walls", s.rotated_walls},
                      {"rotation_min_deg", s.rotation_min_deg},
                      {"rotation_max_deg", s.rotation_max_deg},
                      {"rotation_about", s.rotation_about},
                      {"shortened_walls", s.shortened_walls},
                      {"missing_walls", s.missing_walls},
                      {"extra_walls", s.extra_walls},
                      {"closed_doors", s.closed_doors}};
  // Columns as built came later: written where asked for, so that earlier sweep plans read the
  // same.
  if (s.missing_columns > 0.0) j["missing_columns"] = s.missing_columns;
  if (s.moved_columns > 0.0) j["moved_columns"] = s.moved_columns;
  if (s.shear_deg != 0.0) j["shear_deg"] = s.shear_deg;
  if (s.turn_deg != 0.0) j["turn_deg"] = s.turn_deg;
  if (s.carrier != "legged") j["carrier"] = s.carrier;
  return j;
}

SweepPlan readSweepPlan(const std::string& sweep_dir) {
  const std::string path = (fs::path(sweep_dir) / kSweepPlanFile).string();
  if (!fs::exists(path)) {
    throw common::InputError(path, "",
                             "no such file: " + sweep_dir +
                                 " is not a sweep folder (isg sweep SUITE.json -o DIR makes one)");
  }
  const nlohmann::json document = common::readJsonFile(path);
  const common::JsonSource source{path, nullptr};
  return parseSweepPlan(common::JsonNode(document, "", source));
}

SweepPlan parseSweepPlan(const common::JsonNode& root) {
  common::checkFormatAndVersion(root, "isg.sweep", 1);
  SweepPlan plan;
  plan.name = root.field("name").text();
  plan.suite_file = root.field("suite").text();
  if (root.has("worlds")) {
    for (const auto& w : root.field("worlds").elements()) {
      const std::string name = w.field("name").text();
      plan.world_hashes[name] = w.field("hash").text();
      if (w.has("generate")) plan.world_specs[name] = w.field("generate").raw();
    }
  }
  for (const auto& c : root.field("cells").elements()) {
    SweepCell cell;
    cell.world = c.field("world").text();
    cell.method = c.field("method").text();
    cell.seed = c.field("seed").unsignedInteger();
    cell.dir = c.field("dir").text();
    for (const auto& a : c.field("arguments").elements()) cell.arguments.push_back(a.string());
    if (const auto it = plan.world_hashes.find(cell.world); it != plan.world_hashes.end()) {
      cell.world_hash = it->second;
    }
    plan.cells.push_back(std::move(cell));
  }
  return plan;
}

}  // namespace isg::sweep
