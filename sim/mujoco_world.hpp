#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>

namespace isg::sim {

// A compiled MuJoCo model with its data, owned together. Built from MJCF text through MuJoCo's
// virtual file system, so nothing is written to disk.
class MujocoWorld {
 public:
  // Compiles `mjcf`; throws std::runtime_error with MuJoCo's message if it does not compile.
  static MujocoWorld fromXml(const std::string& mjcf);

  const mjModel& model() const { return *model_; }
  mjData& data() { return *data_; }
  const mjData& data() const { return *data_; }

  void step(int steps = 1);
  double time() const { return data_->time; }

  struct RayHit {
    double distance = -1.0;  // metres along the unit direction
    int geom = -1;
  };
  // mj_ray from `origin` along `direction` (normalised here), seeing only the geom groups set in
  // `groups` (bit g = group g), static geoms included. nullopt when nothing is hit.
  std::optional<RayHit> ray(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            unsigned groups) const;

  std::string geomName(int geom) const;
  int geomId(const std::string& name) const;  // -1 when there is none

 private:
  struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
};

// The groups mask (bit g = group g) that mj_ray takes as an mjtByte[mjNGROUP] array.
std::array<mjtByte, mjNGROUP> groupArray(unsigned groups);

}  // namespace isg::sim
