// libFuzzer harness: bytes → the baseline CSV reader (isg table --baseline), and an accepted table
// written back as CSV and read again: the same cells, every number finite and >= 0 (a nan baseline
// would make the regression gate unable to fail).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "eval/table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  isg::eval::ResultTable table;
  try {
    table = isg::eval::parseTableCsv(text);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  for (const auto& row : table.cells) {
    for (const auto& cell : row) {
      if (cell && (!std::isfinite(*cell) || *cell < 0.0)) std::abort();
    }
  }
  const isg::eval::ResultTable back =
      isg::eval::parseTableCsv(isg::eval::formatTable(table, isg::eval::TableFormat::kCsv));
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      const auto* a = table.find(table.rows[r], table.columns[c]);
      const auto* b = back.find(table.rows[r], table.columns[c]);
      if ((a == nullptr) != (b == nullptr)) std::abort();
      // Written with three decimals: equal to within half a thousandth.
      if (a != nullptr && a->has_value() != b->has_value()) std::abort();
      if (a != nullptr && a->has_value() && std::abs(**a - **b) > 5e-4 * (1 + std::abs(**a))) {
        std::abort();
      }
    }
  }
  return 0;
}
