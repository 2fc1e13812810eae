#include "formats/foxglove_json.hpp"

#include <utility>

namespace isg::formats::foxglove {

namespace {

// Line primitive types (foxglove.LinePrimitive.type).
constexpr int kLineLoop = 1;
constexpr int kLineList = 2;

Json points(const std::vector<Eigen::Vector3d>& ps) {
  Json list = Json::array();
  for (const auto& p : ps) list.push_back(vector3(p));
  return list;
}

Json line(int type, const std::vector<Eigen::Vector3d>& ps, double thickness, const Rgba& c) {
  return {{"type", type},
          {"pose", pose(Eigen::Isometry3d::Identity())},
          {"thickness", thickness},
          {"scale_invariant", false},
          {"points", points(ps)},
          {"color", color(c)},
          {"colors", Json::array()},
          {"indices", Json::array()}};
}

// JSON Schema building blocks for the schemas below.
Json object(Json properties, const std::vector<std::string>& required, const std::string& title) {
  Json schema = {{"type", "object"}, {"properties", std::move(properties)}};
  if (!required.empty()) schema["required"] = required;
  if (!title.empty()) schema["title"] = title;
  return schema;
}
Json numberSchema() { return {{"type", "number"}}; }
Json boolean() { return {{"type", "boolean"}}; }
Json string() { return {{"type", "string"}}; }
Json integer(int minimum, int maximum) {
  return {{"type", "integer"}, {"minimum", minimum}, {"maximum", maximum}};
}
Json arrayOf(Json items) { return {{"type", "array"}, {"items", std::move(items)}}; }
Json timeSchema() {
  return object({{"sec", {{"type", "integer"}, {"minimum", 0}}}, {"nsec", integer(0, 999999999)}},
                {"sec", "nsec"}, "time");
}
Json vector3Schema() {
  return object({{"x", numberSchema()}, {"y", numberSchema()}, {"z", numberSchema()}},
                {"x", "y", "z"}, "foxglove.Vector3");
}
Json quaternionSchema() {
  return object(
      {{"x", numberSchema()}, {"y", numberSchema()}, {"z", numberSchema()}, {"w", numberSchema()}},
      {"x", "y", "z", "w"}, "foxglove.Quaternion");
}
Json poseSchema() {
  return object({{"position", vector3Schema()}, {"orientation", quaternionSchema()}},
                {"position", "orientation"}, "foxglove.Pose");
}
Json colorSchema() {
  return object(
      {{"r", numberSchema()}, {"g", numberSchema()}, {"b", numberSchema()}, {"a", numberSchema()}},
      {"r", "g", "b", "a"}, "foxglove.Color");
}
SchemaText schema(const std::string& name, Json body) {
  body["title"] = name;
  body["$schema"] = "http://json-schema.org/draft-07/schema#";
  return {name, body.dump()};
}

}  // namespace

Json time(RosTime stamp) { return {{"sec", stamp.sec}, {"nsec", stamp.nsec}}; }

Json vector3(const Eigen::Vector3d& v) { return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}}; }

Json quaternion(const Eigen::Quaterniond& q) {
  return {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}};
}

Json pose(const Eigen::Isometry3d& T) {
  return {{"position", vector3(T.translation())},
          {"orientation", quaternion(Eigen::Quaterniond(T.rotation()).normalized())}};
}

Json color(const Rgba& c) { return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}}; }

Json frameTransform(RosTime stamp, const std::string& parent, const std::string& child,
                    const Eigen::Isometry3d& parent_T_child) {
  const Json p = pose(parent_T_child);
  return {{"timestamp", time(stamp)},
          {"parent_frame_id", parent},
          {"child_frame_id", child},
          {"translation", p["position"]},
          {"rotation", p["orientation"]}};
}

Json log(RosTime stamp, LogLevel level, const std::string& message, const std::string& name) {
  return {{"timestamp", time(stamp)},
          {"level", int(level)},
          {"message", message},
          {"name", name},
          {"file", ""},
          {"line", 0}};
}

Json sceneEntity(RosTime stamp, const std::string& frame, const std::string& id) {
  Json entity = {{"timestamp", time(stamp)},
                 {"frame_id", frame},
                 {"id", id},
                 {"lifetime", {{"sec", 0}, {"nsec", 0}}},
                 {"frame_locked", false},
                 {"metadata", Json::array()}};
  for (const char* list :
       {"arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models"}) {
    entity[list] = Json::array();
  }
  return entity;
}

Json cube(const Eigen::Isometry3d& at, const Eigen::Vector3d& size, const Rgba& c) {
  return {{"pose", pose(at)}, {"size", vector3(size)}, {"color", color(c)}};
}

Json sphere(const Eigen::Vector3d& centre, double diameter, const Rgba& c) {
  Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  at.translation() = centre;
  return {{"pose", pose(at)},
          {"size", vector3(Eigen::Vector3d::Constant(diameter))},
          {"color", color(c)}};
}

Json lineList(const std::vector<Eigen::Vector3d>& ps, double thickness, const Rgba& c) {
  return line(kLineList, ps, thickness, c);
}

Json lineLoop(const std::vector<Eigen::Vector3d>& ps, double thickness, const Rgba& c) {
  return line(kLineLoop, ps, thickness, c);
}

Json triangles(const std::vector<Eigen::Vector3d>& ps, const Rgba& c) {
  return {{"pose", pose(Eigen::Isometry3d::Identity())},
          {"points", points(ps)},
          {"color", color(c)},
          {"colors", Json::array()},
          {"indices", Json::array()}};
}

Json text(const Eigen::Vector3d& position, const std::string& words, double font_size,
          const Rgba& c) {
  Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  at.translation() = position;
  return {{"pose", pose(at)},        {"billboard", true}, {"font_size", font_size},
          {"scale_invariant", true}, {"color", color(c)}, {"text", words}};
}

Json sceneUpdate(std::vector<Json> entities) {
  return {{"deletions", Json::array()}, {"entities", Json(std::move(entities))}};
}

SchemaText frameTransformSchema() {
  return schema(
      "foxglove.FrameTransform",
      object({{"timestamp", timeSchema()},
              {"parent_frame_id", string()},
              {"child_frame_id", string()},
              {"translation", vector3Schema()},
              {"rotation", quaternionSchema()}},
             {"timestamp", "parent_frame_id", "child_frame_id", "translation", "rotation"}, ""));
}

SchemaText posesInFrameSchema() {
  return schema("foxglove.PosesInFrame", object({{"timestamp", timeSchema()},
                                                 {"frame_id", string()},
                                                 {"poses", arrayOf(poseSchema())}},
                                                {"timestamp", "frame_id", "poses"}, ""));
}

SchemaText logSchema() {
  return schema("foxglove.Log",
                object({{"timestamp", timeSchema()},
                        {"level", integer(0, 5)},
                        {"message", string()},
                        {"name", string()},
                        {"file", string()},
                        {"line", {{"type", "integer"}, {"minimum", 0}}}},
                       {"timestamp", "level", "message", "name", "file", "line"}, ""));
}

SchemaText sceneUpdateSchema() {
  const Json colors = arrayOf(colorSchema());
  const Json indices = arrayOf({{"type", "integer"}, {"minimum", 0}});
  const Json cube =
      object({{"pose", poseSchema()}, {"size", vector3Schema()}, {"color", colorSchema()}},
             {"pose", "size", "color"}, "foxglove.CubePrimitive");
  Json sphere = cube;
  sphere["title"] = "foxglove.SpherePrimitive";
  const Json line = object(
      {{"type", integer(0, 2)},
       {"pose", poseSchema()},
       {"thickness", {{"type", "number"}, {"minimum", 0}}},
       {"scale_invariant", boolean()},
       {"points", arrayOf(vector3Schema())},
       {"color", colorSchema()},
       {"colors", colors},
       {"indices", indices}},
      {"type", "pose", "thickness", "scale_invariant", "points", "color", "colors", "indices"},
      "foxglove.LinePrimitive");
  const Json triangle =
      object({{"pose", poseSchema()},
              {"points", arrayOf(vector3Schema())},
              {"color", colorSchema()},
              {"colors", colors},
              {"indices", indices}},
             {"pose", "points", "color", "colors", "indices"}, "foxglove.TriangleListPrimitive");
  const Json text = object({{"pose", poseSchema()},
                            {"billboard", boolean()},
                            {"font_size", numberSchema()},
                            {"scale_invariant", boolean()},
                            {"color", colorSchema()},
                            {"text", string()}},
                           {"pose", "billboard", "font_size", "scale_invariant", "color", "text"},
                           "foxglove.TextPrimitive");
  // isg writes no arrows, cylinders or models: those lists are always empty.
  const Json unused = {{"type", "array"}, {"maxItems", 0}};
  const Json entity =
      object({{"timestamp", timeSchema()},
              {"frame_id", string()},
              {"id", string()},
              {"lifetime", object({{"sec", {{"type", "integer"}}}, {"nsec", integer(0, 999999999)}},
                                  {"sec", "nsec"}, "duration")},
              {"frame_locked", boolean()},
              {"metadata", arrayOf(object({{"key", string()}, {"value", string()}},
                                          {"key", "value"}, "foxglove.KeyValuePair"))},
              {"arrows", unused},
              {"cubes", arrayOf(cube)},
              {"spheres", arrayOf(sphere)},
              {"cylinders", unused},
              {"lines", arrayOf(line)},
              {"triangles", arrayOf(triangle)},
              {"texts", arrayOf(text)},
              {"models", unused}},
             {"timestamp", "frame_id", "id", "lifetime", "frame_locked", "metadata", "arrows",
              "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models"},
             "foxglove.SceneEntity");
  const Json deletion =
      object({{"timestamp", timeSchema()}, {"type", integer(0, 1)}, {"id", string()}},
             {"timestamp", "type", "id"}, "foxglove.SceneEntityDeletion");
  return schema("foxglove.SceneUpdate",
                object({{"deletions", arrayOf(deletion)}, {"entities", arrayOf(entity)}},
                       {"deletions", "entities"}, ""));
}

}  // namespace isg::formats::foxglove
