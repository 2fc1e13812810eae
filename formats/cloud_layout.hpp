#pragma once

#include <optional>
#include <string>
#include <vector>

#include "formats/ros_message_decode.hpp"
#include "sensors/messages.hpp"

namespace isg::formats {

// Where a recorded cloud keeps what a scan needs (docs/formats.md, "Importing recordings"),
// fields found by name, any PointField number type:
//   x y z — required;
//   intensity: `intensity`, else `reflectivity` (Ouster), else none (0);
//   ring: `ring` (Velodyne, Ouster), `channel`, `laser_id`, `line` (Livox); else none (0: the
//     localizer then fits planes without the range image);
//   per-point time: `time` (Velodyne: float seconds from the stamp), `t` (Ouster: uint32
//     nanoseconds from the stamp), `offset_time` (Livox: nanoseconds), `timestamp` (Hesai:
//     float64 seconds since the epoch; Livox's PointCloud2 `timestamp`, float64 nanoseconds
//     since the epoch), `time_offset`; integer fields are nanoseconds, floating ones seconds, and
//     a time over 1e6 s is since the epoch (the stamp is subtracted; a floating one in the unit,
//     s, ms, µs or ns, that puts the cloud's first time within 1 s of its stamp).
struct CloudLayout {
  std::optional<ros1::PointField> x, y, z, intensity, ring, time;
  // "x y z intensity ring time (Velodyne)", …: what the import summary says.
  std::string describe() const;
};

// The layout of a cloud's fields; a MessageError when x, y or z is missing, a field's type is
// unknown, its count is not 1 or it lies outside point_step, or the cloud is big-endian.
CloudLayout cloudLayout(const ros1::PointCloud2& cloud);

// The cloud's points in the layout: times in seconds from the cloud's stamp; points without a
// return (a coordinate not finite, or all three zero: Ouster's empty pixels) left out. A
// MessageError when the data is shorter than height × width points or a time is more than 1 s
// from the stamp (not a time from the stamp in any unit this reads).
std::vector<sensors::ScanPoint> cloudPoints(const ros1::PointCloud2& cloud,
                                            const CloudLayout& layout);

// A renumbering of a cloud's rings by elevation, as datasets number them (0 = lowest): entry r is
// ring r's new number. Drivers number rings otherwise (Ouster's and Hesai's from the top beam, raw
// laser ids in firing order); the rings the cloud has are ranked by their points' mean elevation
// and take the numbers they have among them in that order (a ring it lacks keeps its own, so the
// renumbering is one to one). Empty when the rings are in that order already or fewer than two.
std::vector<std::uint16_t> ringsByElevation(const std::vector<sensors::ScanPoint>& points);

}  // namespace isg::formats
