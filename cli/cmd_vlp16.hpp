#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg vlp16 RECORDING: decode a real VLP-16's raw packets (pcap or ROS 2 bag) and report the
// statistics the simulated sensor is compared with (docs/sensors.md). Writes nothing.
class Vlp16Command : public Command {
 public:
  explicit Vlp16Command(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string topic_;
  double cut_deg_ = 0.0;
  double min_range_ = 0.4;
  double max_range_ = 130.0;
  std::string interpolation_ = "per-sequence";
  bool json_ = false;
};

}  // namespace isg::cli
