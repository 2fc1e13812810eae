#include "run/run_folder.hpp"

#include <algorithm>
#include <filesystem>
#include <span>

#include "bim/agraph_json.hpp"
#include "common/atomic_folder.hpp"
#include "common/tum.hpp"
#include "run/deviation_report.hpp"
#include "run/run_report.hpp"

namespace isg::run {

namespace fs = std::filesystem;

namespace {

// A TUM file written 8192 poses at a time: two hours of ground truth at 100 Hz are ~80 MB of text.
void writeTumFile(const fs::path& path, common::PoseSequence trajectory) {
  constexpr std::size_t kPart = 8192;
  std::size_t next = 0;
  Trajectory part;
  common::writeFileInParts(path, [&] {
    const std::size_t count = std::min(kPart, trajectory.size() - next);
    part.clear();
    for (std::size_t i = next; i < next + count; ++i) part.push_back(trajectory[i]);
    next += count;
    return common::toTumText(part);
  });
}

}  // namespace

void writeRunFolder(const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation,
                    bool force, const std::function<void(const fs::path& folder)>& more_files) {
  common::writeFolderAtomically(
      dir, common::OutputKind::kRunFolder, force, [&](const fs::path& temporary) {
        writeTumFile(temporary / "groundtruth.tum", run.streams.ground_truth);
        // No odometry stream (a handheld carrier, a recording without it): no odometry.tum.
        if (!run.streams.odometry.empty()) {
          writeTumFile(temporary / "odometry.tum", run.streams.odometry);
        }
        writeTumFile(temporary / "estimate.tum", run.estimate);
        common::writeFile(temporary / "estimate_states.txt",
                          estimateStatesText(run.estimate, run.estimate_states));
        writeTumFile(temporary / "estimate_map.tum", run.estimate_map);
        common::writeFile(temporary / kMetricsFile,
                          metricsToJson(evaluation.metrics).dump(2) + "\n");
        if (run.setup.agraph) {
          common::writeFile(temporary / "agraph.json",
                            bim::agraphJsonText(bim::agraphToJson(*run.setup.agraph)));
        }
        common::writeFile(temporary / "sgraph.json", run.graph.dump(1) + "\n");
        if (run.map) {
          Trajectory keyframes;
          for (const auto& kf : run.map->keyframes) keyframes.push_back({kf.stamp, kf.estimate});
          common::writeFile(temporary / "keyframes.tum", common::toTumText(keyframes));
        }
        common::writeFile(temporary / "report.svg", reportSvg(run, evaluation));
        if (evaluation.deviations) {
          common::writeFile(temporary / "deviations.json",
                            deviationReportJson(*evaluation.deviations).dump(1) + "\n");
          common::writeFile(temporary / "deviations.svg", deviationSvg(*evaluation.deviations));
        }
        if (more_files) more_files(temporary);
      });
}

}  // namespace isg::run
