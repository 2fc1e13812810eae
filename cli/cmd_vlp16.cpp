#include "cli/cmd_vlp16.hpp"

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "formats/vlp16_recording.hpp"
#include "formats/vlp16_statistics.hpp"

namespace isg::cli {

namespace {

const char* modeName(formats::Vlp16ReturnMode mode) {
  switch (mode) {
    case formats::Vlp16ReturnMode::kStrongest:
      return "strongest";
    case formats::Vlp16ReturnMode::kLast:
      return "last";
    case formats::Vlp16ReturnMode::kDual:
      return "dual";
  }
  return "?";
}

}  // namespace

Vlp16Command::Vlp16Command(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "vlp16", "Decode a real VLP-16's raw packets and report its return statistics");
  app_->footer(
      "RECORDING is a pcap capture (.pcap: UDP datagrams of 1206 bytes are data packets) or a ROS "
      "2 bag in the sqlite3 storage (its folder or a .db3 file) of "
      "velodyne_msgs/msg/VelodyneScan messages. It reports the share of laser shots without an "
      "echo per ring (0 = -15 deg), the reflectivity's median and 99th percentile and the returns "
      "per complete turn: the numbers docs/simulation.md compares the simulated sensor with. "
      "The decoder and its conventions: docs/sensors.md. Writes nothing.");
  app_->add_option("recording", input_, "pcap file or ROS 2 bag")
      ->option_text("RECORDING")
      ->required();
  app_->add_option("--topic", topic_,
                   "the bag's VelodyneScan topic (default: the only topic of that type)");
  app_->add_option("--cut-deg", cut_deg_, "azimuth where a turn begins, degrees [0, 360)")
      ->check(numberIn(0.0, 359.99))
      ->capture_default_str();
  app_->add_option("--min-range", min_range_, "returns nearer than this are dropped, m")
      ->check(nonNegativeNumber())
      ->capture_default_str();
  app_->add_option("--max-range", max_range_, "returns farther than this are dropped, m")
      ->check(positiveNumber())
      ->capture_default_str();
  app_->add_option("--interpolation", interpolation_,
                   "the decoder's conventions (azimuth interpolation, dual-mode firing times): "
                   "per-sequence, or nebula (tier4/nebula's decoder)")
      ->check(CLI::IsMember({"per-sequence", "nebula"}))
      ->capture_default_str();
  app_->add_flag("--json", json_, "print the statistics as JSON");
}

int Vlp16Command::run() {
  if (!(min_range_ < max_range_)) {
    std::cerr << "isg vlp16: --min-range (" << min_range_ << ") must be below --max-range ("
              << max_range_ << ")\n";
    return kExitUsage;
  }
  formats::Vlp16DecodeOptions options;
  options.min_range = min_range_;
  options.max_range = max_range_;
  options.convention = interpolation_ == "nebula" ? formats::Vlp16Convention::kNebula
                                                  : formats::Vlp16Convention::kPerSequence;
  const auto recording = formats::readVlp16Recording(input_, options, topic_);
  const auto turns = formats::cutIntoTurns(recording.points, cut_deg_);
  const auto stats = formats::vlp16Statistics(recording.tally, turns);
  if (json_) {
    nlohmann::ordered_json out;
    out["recording"] = input_;
    out["return_mode"] = modeName(recording.mode);
    out["data_packets"] = recording.data_packets;
    out["position_packets"] = recording.position_packets;
    out["returns"] = recording.points.size();
    out["complete_turns"] = stats.complete_turns;
    out["lost"] = stats.lost;
    out["lost_by_ring"] = stats.lost_by_ring;
    out["intensity_median"] = stats.intensity_median;
    out["intensity_p99"] = stats.intensity_p99;
    out["intensity_max"] = stats.intensity_max;
    out["points_per_turn"] = stats.points_per_turn;
    out["turn_duration_s"] = stats.turn_duration;
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("isg vlp16: %s: %zu data packets (%s return), %zu position packets, %zu returns\n",
              input_.c_str(), recording.data_packets, modeName(recording.mode),
              recording.position_packets, recording.points.size());
  std::printf("  shots without an echo: %.1f %%; by ring (-15 ... +15 deg):", 100.0 * stats.lost);
  for (double lost : stats.lost_by_ring) std::printf(" %.0f", 100.0 * lost);
  std::printf(" %%\n");
  std::printf("  reflectivity: median %.0f, 99th percentile %.0f, max %.0f\n",
              stats.intensity_median, stats.intensity_p99, stats.intensity_max);
  if (stats.complete_turns == 0) {
    std::printf("  no complete turn (a recording shorter than two turns): no per-turn numbers\n");
  } else {
    std::printf("  per complete turn (%d of them): %.0f returns over %.4f s\n",
                stats.complete_turns, stats.points_per_turn, stats.turn_duration);
  }
  return kExitOk;
}

}  // namespace isg::cli
