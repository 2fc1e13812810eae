#include "cli/bcf_report.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "run/bcf/bcf_archive.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/renderer.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::cli {

namespace {

constexpr int kSnapshotWidth = 800;
constexpr int kSnapshotHeight = 600;  // 4:3, TopicCamera::aspect

// The building and a renderer, made at the first snapshot: a report without topics costs nothing.
class Snapshots {
 public:
  Snapshots(const bim::Plan& plan, const bim::AsBuilt* as_built)
      : plan_(plan), as_built_(as_built) {}

  std::string operator()(const run::bcf::Topic& topic) {
    if (failed_) return "";
    if (!renderer_) {
      // A machine that cannot render (no EGL) still gets the report, without pictures: the run
      // it ends is not lost for them.
      try {
        world_ = std::make_unique<sim::MujocoWorld>(sim::MujocoWorld::fromXml(
            worlds::generateMjcf(plan_, as_built_ ? *as_built_ : bim::AsBuilt{})));
        renderer_ =
            std::make_unique<sim::Renderer>(world_->model(), kSnapshotWidth, kSnapshotHeight);
      } catch (const std::runtime_error& error) {
        std::fprintf(stderr, "warning: deviations.bcf has no snapshots: %s\n", error.what());
        failed_ = true;
        return "";
      }
    }
    std::vector<sim::Renderer::Line> lines;
    for (const auto& [from, to] : topic.outline.edges()) lines.push_back({from, to});
    const run::bcf::TopicCamera& camera = topic.camera;
    return sim::pngBytes(renderer_->lookAt(world_->data(), camera.eye, camera.target,
                                           camera.vertical_fov_deg, lines));
  }

 private:
  const bim::Plan& plan_;
  const bim::AsBuilt* as_built_;
  std::unique_ptr<sim::MujocoWorld> world_;
  std::unique_ptr<sim::Renderer> renderer_;
  bool failed_ = false;
};

}  // namespace

std::size_t writeDeviationBcf(const std::filesystem::path& file, const BcfSources& sources) {
  const std::vector<run::bcf::Topic> topics =
      run::bcf::deviationTopics(*sources.report, *sources.plan, sources.names);
  run::bcf::ArchiveOptions options;
  options.created = run::bcf::creationTime();
  auto snapshots = std::make_shared<Snapshots>(*sources.plan, sources.as_built);
  if (sources.snapshots) options.snapshot = [snapshots](const auto& t) { return (*snapshots)(t); };
  run::bcf::writeArchive(file, topics, options);
  return topics.size();
}

}  // namespace isg::cli
