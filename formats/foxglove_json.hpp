#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "formats/ros_time.hpp"

namespace isg::formats::foxglove {

// Foxglove's own message types in their JSON encoding (docs/foxglove.md): what its 3D, Log and
// Raw Messages panels read without ROS. Every object carries every field the type's JSON Schema
// requires, empty lists included, so that a message validates against Foxglove's schemas.

using Json = nlohmann::json;

struct Rgba {
  double r = 0, g = 0, b = 0, a = 1;
};

// foxglove.Time: {sec, nsec}.
Json time(RosTime stamp);
Json vector3(const Eigen::Vector3d& v);
Json quaternion(const Eigen::Quaterniond& q);
// foxglove.Pose of `T` (position, orientation).
Json pose(const Eigen::Isometry3d& T);
Json color(const Rgba& c);

// foxglove.FrameTransform: `child` placed in `parent` by parent_T_child.
Json frameTransform(RosTime stamp, const std::string& parent, const std::string& child,
                    const Eigen::Isometry3d& parent_T_child);

// foxglove.Log levels.
enum class LogLevel { kDebug = 1, kInfo = 2, kWarning = 3, kError = 4 };
// foxglove.Log: `message` from `name` (no source file: file "" and line 0).
Json log(RosTime stamp, LogLevel level, const std::string& message, const std::string& name);

// A foxglove.SceneEntity with no primitives yet (every primitive list present and empty), never
// expiring (lifetime 0), not frame-locked.
Json sceneEntity(RosTime stamp, const std::string& frame, const std::string& id);
// Primitives, appended to an entity's lists ("cubes", "spheres", "lines", "triangles", "texts").
Json cube(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size, const Rgba& c);
Json sphere(const Eigen::Vector3d& centre, double diameter, const Rgba& c);
// A LINE_LIST: every two points one segment; `thickness` in metres.
Json lineList(const std::vector<Eigen::Vector3d>& points, double thickness, const Rgba& c);
// A LINE_LOOP through `points`.
Json lineLoop(const std::vector<Eigen::Vector3d>& points, double thickness, const Rgba& c);
// A triangle list: every three points one triangle.
Json triangles(const std::vector<Eigen::Vector3d>& points, const Rgba& c);
// Text facing the viewer, `font_size` in pixels (scale-invariant).
Json text(const Eigen::Vector3d& position, const std::string& words, double font_size,
          const Rgba& c);
// foxglove.SceneUpdate: replaces the entities of the same id on its topic.
Json sceneUpdate(std::vector<Json> entities);

// The names and JSON Schemas (as an MCAP Schema record with encoding "jsonschema" carries them)
// of the types above, written for what isg emits: every field it writes, typed, with Foxglove's
// required lists.
struct SchemaText {
  std::string name;  // "foxglove.SceneUpdate"
  std::string json_schema;
};
SchemaText frameTransformSchema();
SchemaText posesInFrameSchema();
SchemaText logSchema();
SchemaText sceneUpdateSchema();

}  // namespace isg::formats::foxglove
