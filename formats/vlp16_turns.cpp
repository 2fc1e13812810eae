#include "formats/vlp16_turns.hpp"

#include <cmath>
#include <cstdint>

namespace isg::formats {

std::vector<Vlp16Turn> cutIntoTurns(const std::vector<Vlp16Point>& points, double cut_deg) {
  constexpr std::int64_t kTurnInHundredths = 36000;
  const auto cut = std::int64_t(std::llround(cut_deg * 100.0)) % kTurnInHundredths;
  std::vector<Vlp16Turn> turns;
  std::int64_t unwrapped = 0;   // the head's azimuth summed along the firing order
  std::int64_t first_turn = 0;  // turn number of turns[0]
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::int64_t azimuth = points[i].azimuth;
    if (i == 0) {
      unwrapped = azimuth;
    } else {
      // The shortest way round from the previous firing: a turn never advances half a turn
      // between two firings, and the second echo of a pair may sit a step behind the first.
      std::int64_t delta = (azimuth - points[i - 1].azimuth) % kTurnInHundredths;
      if (delta > kTurnInHundredths / 2) delta -= kTurnInHundredths;
      if (delta <= -kTurnInHundredths / 2) delta += kTurnInHundredths;
      unwrapped += delta;
    }
    const std::int64_t shifted = unwrapped - cut;
    const std::int64_t turn =
        shifted >= 0 ? shifted / kTurnInHundredths : -((-shifted - 1) / kTurnInHundredths) - 1;
    if (turns.empty()) first_turn = turn;
    const std::int64_t index = turn - first_turn;
    if (index < 0) continue;  // a straggler behind the first crossing of the recording
    while (std::int64_t(turns.size()) <= index) turns.emplace_back();
    turns[std::size_t(index)].points.push_back(points[i]);
  }
  for (std::size_t t = 0; t < turns.size(); ++t) {
    turns[t].complete = t > 0 && t + 1 < turns.size();
  }
  return turns;
}

}  // namespace isg::formats
