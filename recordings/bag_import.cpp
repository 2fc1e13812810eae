#include "recordings/bag_import.hpp"

#include "recordings/bag_import_parts.hpp"

namespace isg::recordings {
namespace bag_import {

BagImportSummary Import::run(const fs::path& folder,
                             const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  collectTopics();
  chooseTopics();
  readStatic();
  resolveFrames();
  readStreams(folder, progress);
  writeFiles(folder);
  return summary_;
}

}  // namespace bag_import

BagImportSummary importRosbag(const std::string& bag_path, const std::string& dataset_dir,
                              const BagImportOptions& options,
                              const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  bag_import::Import import(bag_path, options);
  BagImportSummary summary;
  common::writeFolderAtomically(
      dataset_dir, common::OutputKind::kDataset, options.overwrite,
      [&](const std::filesystem::path& folder) { summary = import.run(folder, progress); });
  return summary;
}

}  // namespace isg::recordings
