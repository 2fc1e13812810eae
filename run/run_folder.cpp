#include "run/run_folder.hpp"

#include <filesystem>

#include "bim/agraph_json.hpp"
#include "run/deviation_report.hpp"
#include "run/run_report.hpp"
#include "sensors/atomic_folder.hpp"

namespace isg::run {

namespace fs = std::filesystem;

void writeRunFolder(const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation,
                    bool force) {
  sensors::writeFolderAtomically(
      dir, sensors::OutputKind::kRunFolder, force, [&](const fs::path& temporary) {
        sensors::writeFile(temporary / "groundtruth.tum",
                           eval::toTumText(run.streams.ground_truth));
        // No odometry stream (a handheld carrier, a recording without it): no odometry.tum.
        if (!run.streams.odometry.empty()) {
          sensors::writeFile(temporary / "odometry.tum", eval::toTumText(run.streams.odometry));
        }
        sensors::writeFile(temporary / "estimate.tum", eval::toTumText(run.estimate));
        sensors::writeFile(temporary / "estimate_map.tum", eval::toTumText(run.estimate_map));
        sensors::writeFile(temporary / kMetricsFile,
                           metricsToJson(evaluation.metrics).dump(2) + "\n");
        if (run.setup.agraph) {
          sensors::writeFile(temporary / "agraph.json",
                             bim::agraphJsonText(bim::agraphToJson(*run.setup.agraph)));
        }
        sensors::writeFile(temporary / "sgraph.json", run.graph.dump(1) + "\n");
        if (run.map) {
          Trajectory keyframes;
          for (const auto& kf : run.map->keyframes) keyframes.push_back({kf.stamp, kf.estimate});
          sensors::writeFile(temporary / "keyframes.tum", eval::toTumText(keyframes));
        }
        sensors::writeFile(temporary / "report.svg", reportSvg(run, evaluation));
        if (evaluation.deviations) {
          sensors::writeFile(temporary / "deviations.json",
                             deviationReportJson(*evaluation.deviations).dump(1) + "\n");
          sensors::writeFile(temporary / "deviations.svg", deviationSvg(*evaluation.deviations));
        }
      });
}

}  // namespace isg::run
