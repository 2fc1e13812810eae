#pragma once

#include <optional>

#include "common/pose_track.hpp"
#include "common/tum.hpp"

namespace isg::eval {

// Wrong localization (docs/evaluation.md): a global localizer that reports a pose in B more than
// `max_error` off the ground truth in the plane, or more than `max_height_error` off in height (on
// another floor), is wrongly localized at that row. A run is *wrong* when
// such rows follow each other for longer than `max_duration` seconds: once, briefly, may be a
// transient; for seconds on end it is a robot driving on a false belief.
struct WrongLocalizationOptions {
  double max_error = 1.0;  // m
  // Storeys are at least 2 m apart (docs/formats.md): half of that is on another floor.
  double max_height_error = 1.0;  // m
  double max_duration = 5.0;      // s
  // Consecutive estimate rows further apart than this are not one stretch: the localizer stopped
  // reporting between them (lost), so that time is not counted as wrong.
  double max_gap = 1.0;    // s
  double max_diff = 0.01;  // s, associating estimate rows with ground-truth stamps (as APE)
};

struct WrongLocalization {
  double seconds = 0.0;  // time covered by consecutive rows both more than max_error off
  double longest = 0.0;  // the longest such stretch, seconds
  bool wrong = false;    // longest > max_duration
  std::optional<double> first_wrong_at;  // stamp where the first stretch > max_duration began
  double max_error = 0.0;                // m, the largest 2D error of any associated row
  double max_height_error = 0.0;         // m, the largest height error of any associated row
};

WrongLocalization wrongLocalization(common::PoseSequence ground_truth,
                                    common::PoseSequence estimate,
                                    const WrongLocalizationOptions& options = {});

}  // namespace isg::eval
