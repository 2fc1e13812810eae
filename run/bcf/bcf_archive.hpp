#pragma once

#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "run/bcf/bcf_topics.hpp"

namespace isg::run::bcf {

// A topic's snapshot as PNG bytes; empty: the topic has none.
using SnapshotMaker = std::function<std::string(const Topic& topic)>;

struct ArchiveOptions {
  std::time_t created = 0;     // every topic's creation date and every entry's time (UTC)
  std::string author = "isg";  // the topics' CreationAuthor
  SnapshotMaker snapshot;      // none: no snapshots
};

// Writes the BCF 3.0 archive (a zip, docs/deviations.md "BCF") to `path`: bcf.version and
// extensions.xml first (both stored, the latter marked as isg's, so that a later write may
// replace it), then one folder per topic with markup.bcf, viewpoint.bcfv and snapshot.png, each
// folder with its own directory entry as buildingSMART's encoding guide asks. The same topics,
// date and snapshots give the same bytes. Throws common::InputError naming `path` when it cannot
// be written.
void writeArchive(const std::filesystem::path& path, const std::vector<Topic>& topics,
                  const ArchiveOptions& options);

// When a report is dated: SOURCE_DATE_EPOCH when the environment sets it (reproducible builds'
// convention: the same files from the same run), else now. Throws common::InputError when it is
// set to something that is not a whole number of seconds.
std::time_t creationTime();

}  // namespace isg::run::bcf
