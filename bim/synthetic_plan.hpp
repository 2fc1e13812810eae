#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>

namespace isg::bim {

// A rectangular grid of rooms, for scale tests and benchmarks: `rows` × `cols` rooms separated by
// long walls that run the whole building (so each wall bounds many rooms and meets many others
// in T-junctions), a door between every pair of neighbouring rooms and one to the outside.
// Room sizes vary from column to column and row to row so that no two neighbours are alike.
struct GridPlanSpec {
  int rows = 10;
  int cols = 20;
  double cell_width = 4.0;  // mean, metres
  double cell_depth = 3.5;  // mean, metres
  double wall_thickness = 0.15;
  double height = 3.0;
  bool give_door_rooms = false;  // false: doors leave "rooms" out and the parser infers them
  // 0: sizes vary in a fixed pattern of period 8 (so a wide grid repeats itself, as real
  // buildings do); otherwise each row and column size is drawn, ±20 %, from this seed.
  std::uint64_t size_seed = 0;
};

// The plan as a JSON document in the "isg.plan" v1 format.
nlohmann::json makeGridPlan(const GridPlanSpec& spec);

}  // namespace isg::bim
