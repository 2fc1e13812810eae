#include "bim/floor_at.hpp"

namespace isg::bim {

int floorAt(const AGraph& graph, double z) {
  int best = -1, lowest = -1;
  for (int f = 0; f < int(graph.floors.size()); ++f) {
    const double elevation = graph.floors[f].elevation;
    if (lowest < 0 || elevation < graph.floors[lowest].elevation) lowest = f;
    if (elevation <= z && (best < 0 || elevation > graph.floors[best].elevation)) best = f;
  }
  return best >= 0 ? best : lowest;
}

}  // namespace isg::bim
