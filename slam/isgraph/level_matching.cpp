#include "slam/isgraph/level_matching.hpp"

#include <map>

namespace isg::slam {

LevelGraph levelGraph(const bim::AGraph& whole, int floor) {
  LevelGraph out;
  out.floor = floor;
  const std::string& level = whole.floors[floor].id;
  bim::AGraph& g = out.graph;
  g.plan_name = whole.plan_name;
  std::map<int, int> surface_here, room_here;  // whole index → this graph's
  for (int i = 0; i < int(whole.surfaces.size()); ++i) {
    if (whole.surfaces[i].level != level) continue;
    surface_here[i] = int(g.surfaces.size());
    out.surface_in_whole.push_back(i);
    g.surfaces.push_back(whole.surfaces[i]);
  }
  auto surface = [&](int i) {
    const auto it = surface_here.find(i);
    return it == surface_here.end() ? -1 : it->second;
  };
  for (const auto& wall : whole.walls) {
    if (wall.level != level) continue;
    bim::WallNode copy = wall;
    copy.left_surface = surface(wall.left_surface);
    copy.right_surface = surface(wall.right_surface);
    g.walls.push_back(copy);
  }
  for (int i = 0; i < int(whole.rooms.size()); ++i) {
    if (whole.rooms[i].floor != floor) continue;
    room_here[i] = int(g.rooms.size());
    out.room_in_whole.push_back(i);
    bim::RoomNode copy = whole.rooms[i];
    for (int& s : copy.surfaces) s = s >= 0 ? surface(s) : -1;
    for (auto& pair : copy.pairs) pair = {surface(pair[0]), surface(pair[1])};
    copy.floor = 0;
    g.rooms.push_back(std::move(copy));
  }
  for (const auto& doorway : whole.doorways) {
    if (doorway.level != level) continue;
    bim::DoorwayNode copy = doorway;
    copy.rooms.clear();
    for (int r : doorway.rooms) {
      const auto it = room_here.find(r);
      if (it != room_here.end()) copy.rooms.push_back(it->second);
    }
    g.doorways.push_back(std::move(copy));
  }
  bim::FloorNode node = whole.floors[floor];
  node.rooms.clear();
  for (int r : whole.floors[floor].rooms) {
    const auto it = room_here.find(r);
    if (it != room_here.end()) node.rooms.push_back(it->second);
  }
  g.floors.push_back(std::move(node));
  return out;
}

LevelMatcher::LevelMatcher(const bim::AGraph& whole, const MatchingOptions& options)
    : whole_(&whole) {
  for (int f = 0; f < int(whole.floors.size()); ++f) {
    Level& level = levels_.emplace_back();
    level.graph = levelGraph(whole, f);
    level.matcher = std::make_unique<GraphMatcher>(level.graph.graph, options);
  }
}

Verification LevelMatcher::inWhole(const Verification& v, int level) const {
  const LevelGraph& g = levels_[level].graph;
  Verification out = v;
  for (auto& [s, a] : out.planes) a = g.surface_in_whole[a];
  for (auto& [s, a] : out.rooms) a = g.room_in_whole[a];
  return out;
}

Verification LevelMatcher::verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw,
                                  int level) const {
  return inWhole(levels_[level].matcher->verify(input, x_y_yaw), level);
}

LevelMatch LevelMatcher::match(const MatchInput& input, ThreadPool* pool) const {
  std::vector<MatchResult> results;
  double seconds = 0.0;
  int hypotheses = 0, clusters = 0;
  for (const Level& level : levels_) {
    results.push_back(level.matcher->match(input, pool));
    seconds += results.back().seconds;
    hypotheses += results.back().hypotheses;
    clusters += results.back().clusters;
  }
  auto adequate = [](const MatchResult& r) {
    return r.status == MatchStatus::kMatched || r.status == MatchStatus::kAmbiguous;
  };
  // The best answer among the levels where one explains the map well enough; else the level
  // with the highest score says why none does.
  int best = -1, top = 0;
  for (int l = 0; l < int(results.size()); ++l) {
    if (results[l].best.score > results[top].best.score) top = l;
    if (adequate(results[l]) && (best < 0 || results[l].best.score > results[best].best.score)) {
      best = l;
    }
  }
  auto in_whole = [&](const MatchResult& r, int level) {
    MatchResult out = r;
    out.best = inWhole(r.best, level);
    out.second = inWhole(r.second, level);
    for (Candidate& c : out.candidates) c.answer = inWhole(c.answer, level);
    out.seconds = seconds;
    out.hypotheses = hypotheses;
    out.clusters = clusters;
    return out;
  };
  LevelMatch out;
  const std::string& top_id = whole_->floors[levels_[top].graph.floor].id;
  if (best < 0) {
    out.result = in_whole(results[top], top);
    out.result.reason = "best on level " + top_id + ": " + out.result.reason;
    return out;
  }
  const GraphMatcher& matcher = *levels_[best].matcher;
  out.result = in_whole(results[best], best);
  out.level = levels_[best].graph.floor;
  const std::string& best_id = whole_->floors[out.level].id;
  // Against every other level's best answer, on the evidence where the two disagree.
  std::string alike;
  for (int l = 0; l < int(results.size()); ++l) {
    if (l == best || results[l].hypotheses == 0 || results[l].best.score <= 0.0) continue;
    const Distinction d =
        matcher.distinguish(input, results[best].best, results[l].best, levels_[l].matcher.get());
    if (matcher.decisive(d)) continue;
    out.alike_levels.push_back(levels_[l].graph.floor);
    out.result.candidates.insert(out.result.candidates.begin(),
                                 Candidate{inWhole(results[l].best, l), d});
    alike += (alike.empty() ? "" : ", ") + whole_->floors[levels_[l].graph.floor].id;
  }
  if (out.alike_levels.empty()) {
    out.result.reason = "on level " + best_id + ": " + out.result.reason;
    return out;
  }
  out.result.status = MatchStatus::kAmbiguous;
  out.result.second = out.result.candidates.front().answer;
  out.result.second_score = out.result.second.score;
  out.result.reason = "levels " + best_id + " and " + alike + " explain the map alike (" +
                      out.result.candidates.front().from_best.describe() +
                      "); something only one of them has would separate them; on level " + best_id +
                      ": " + out.result.reason;
  return out;
}

}  // namespace isg::slam
