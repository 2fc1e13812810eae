#include "sim/mujoco_world.hpp"

#include <cstring>
#include <stdexcept>

namespace isg::sim {

std::array<mjtByte, mjNGROUP> groupArray(unsigned groups) {
  std::array<mjtByte, mjNGROUP> out{};
  for (int g = 0; g < mjNGROUP; ++g) out[g] = (groups >> g) & 1u;
  return out;
}

MujocoWorld MujocoWorld::fromXml(const std::string& mjcf) {
  // mjVFS holds fixed arrays of file names and pointers: too large for the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  constexpr const char* kName = "world.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(mjcf.size())) != 0) {
    throw std::runtime_error("MuJoCo: cannot create the in-memory model file");
  }
  const int index = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[index], mjcf.data(), mjcf.size());
  char error[1024] = "";
  mjModel* model = mj_loadXML(kName, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (model == nullptr)
    throw std::runtime_error(std::string("MuJoCo could not compile the world: ") + error);
  MujocoWorld world;
  world.model_.reset(model);
  world.data_.reset(mj_makeData(model));
  mj_forward(world.model_.get(), world.data_.get());
  return world;
}

void MujocoWorld::step(int steps) {
  for (int i = 0; i < steps; ++i) mj_step(model_.get(), data_.get());
}

std::optional<MujocoWorld::RayHit> MujocoWorld::ray(const Eigen::Vector3d& origin,
                                                    const Eigen::Vector3d& direction,
                                                    unsigned groups) const {
  const Eigen::Vector3d unit = direction.normalized();
  const auto mask = groupArray(groups);
  int geom = -1;
  const double distance =
      mj_ray(model_.get(), data_.get(), origin.data(), unit.data(), mask.data(), 1, -1, &geom);
  if (distance < 0) return std::nullopt;
  return RayHit{distance, geom};
}

std::string MujocoWorld::geomName(int geom) const {
  const char* name = mj_id2name(model_.get(), mjOBJ_GEOM, geom);
  return name ? name : "";
}

int MujocoWorld::geomId(const std::string& name) const {
  return mj_name2id(model_.get(), mjOBJ_GEOM, name.c_str());
}

}  // namespace isg::sim
