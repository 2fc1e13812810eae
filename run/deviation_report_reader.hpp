#pragma once

#include <string>

#include "common/json_reader.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run {

// deviations.json read back (docs/deviations.md), the reader beside its one writer
// (run::deviationReportJson): every field the writer writes, into the report it was written from.
// What the file does not hold stays at its default: a wall's thickness and confirmed spans, the
// keyframes' placements, the columns' outlines. Reading what the writer wrote and writing it again
// gives the same document (run/tests/deviation_report_reader_test.cpp). A document that is not
// one (a missing field, a number where a string goes, an unknown status) is an InputError naming
// the file and the JSON pointer.
slam::DeviationReport readDeviationReport(const common::JsonNode& root);

// The file at `path` (at most 256 MB).
slam::DeviationReport loadDeviationReport(const std::string& path);

}  // namespace isg::run
