#include "run/method_options.hpp"

#include <cmath>
#include <stdexcept>

#include "common/json_reader.hpp"

namespace isg::run {

double MethodOptions::number(const std::string& key, double fallback, double lo, double hi) {
  known_.insert(key);
  const auto it = options_.find(key);
  if (it == options_.end()) return effective_[key] = fallback;
  std::size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(it->second, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != it->second.size() || !(value >= lo && value <= hi)) {
    throw std::invalid_argument(key + "=" + it->second + ": " + method_ + "'s " + key +
                                " must be a number in [" + common::formatNumber(lo) + ", " +
                                common::formatNumber(hi) + "]");
  }
  return effective_[key] = value;
}

int MethodOptions::integer(const std::string& key, int fallback, int lo, int hi) {
  const double value = number(key, fallback, lo, hi);
  if (value != std::floor(value)) {
    throw std::invalid_argument(key + "=" + options_.at(key) + ": " + method_ + "'s " + key +
                                " must be a whole number");
  }
  return int(value);
}

void MethodOptions::finish() const {
  for (const auto& [key, value] : options_) {
    if (known_.count(key)) continue;
    std::string known;
    for (const auto& k : known_) known += (known.empty() ? "" : ", ") + k;
    throw std::invalid_argument(key + "=" + value + ": " + method_ + " has no option " + key +
                                (known.empty() ? " (it has none)" : " (it has " + known + ")"));
  }
}

}  // namespace isg::run
