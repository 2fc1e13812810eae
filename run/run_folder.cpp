#include "run/run_folder.hpp"

#include <filesystem>

#include "bim/agraph_json.hpp"
#include "common/atomic_folder.hpp"
#include "common/tum.hpp"
#include "run/deviation_report.hpp"
#include "run/run_report.hpp"

namespace isg::run {

namespace fs = std::filesystem;

void writeRunFolder(const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation,
                    bool force) {
  common::writeFolderAtomically(
      dir, common::OutputKind::kRunFolder, force, [&](const fs::path& temporary) {
        common::writeFile(temporary / "groundtruth.tum",
                          common::toTumText(run.streams.ground_truth));
        // No odometry stream (a handheld carrier, a recording without it): no odometry.tum.
        if (!run.streams.odometry.empty()) {
          common::writeFile(temporary / "odometry.tum", common::toTumText(run.streams.odometry));
        }
        common::writeFile(temporary / "estimate.tum", common::toTumText(run.estimate));
        common::writeFile(temporary / "estimate_map.tum", common::toTumText(run.estimate_map));
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
      });
}

}  // namespace isg::run
