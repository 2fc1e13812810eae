#include "run/run_folder.hpp"

#include <filesystem>

#include "bim/agraph_json.hpp"
#include "run/atomic_folder.hpp"
#include "run/run_report.hpp"

namespace isg::run {

namespace fs = std::filesystem;

void writeRunFolder(const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation,
                    bool force) {
  writeFolderAtomically(dir, OutputKind::kRunFolder, force, [&](const fs::path& temporary) {
    writeFile(temporary / "groundtruth.tum", eval::toTumText(run.streams.ground_truth));
    writeFile(temporary / "odometry.tum", eval::toTumText(run.streams.odometry));
    writeFile(temporary / "estimate.tum", eval::toTumText(run.estimate));
    writeFile(temporary / "estimate_map.tum", eval::toTumText(run.estimate_map));
    writeFile(temporary / kMetricsFile, metricsToJson(evaluation.metrics).dump(2) + "\n");
    if (run.setup.agraph) {
      writeFile(temporary / "agraph.json",
                bim::agraphJsonText(bim::agraphToJson(*run.setup.agraph)));
    }
    writeFile(temporary / "sgraph.json", run.graph.dump(1) + "\n");
    if (run.map) {
      Trajectory keyframes;
      for (const auto& kf : run.map->keyframes) keyframes.push_back({kf.stamp, kf.estimate});
      writeFile(temporary / "keyframes.tum", eval::toTumText(keyframes));
    }
    writeFile(temporary / "report.svg", reportSvg(run, evaluation));
  });
}

}  // namespace isg::run
