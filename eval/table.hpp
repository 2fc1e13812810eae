#pragma once

#include <optional>
#include <string>
#include <vector>

namespace isg::eval {

// What a cell's runs (one per seed) add up to: how many there were, how many localized correctly
// (a number, not wrong), how many were wrongly localized, and the mean and sample standard
// deviation of the numbers of the correct ones.
struct CellStats {
  int runs = 0;
  int localized = 0;  // correctly: a number and not wrong
  int wrong = 0;
  // Of `runs`, the seeds a sweep asked for that have no result: the run failed, or has not run.
  int failed = 0;
  int not_run = 0;
  std::optional<double> mean;  // over the correct runs
  std::optional<double> std;   // sample (n − 1) standard deviation; needs two correct runs
};

// The statistics of a cell's values, one per run (nullopt: never localized), `wrong` flags run
// by run.
CellStats cellStats(const std::vector<std::optional<double>>& values,
                    const std::vector<bool>& wrong);

// The label of the last row: how many rows each column localized correctly (a number, not ✗).
inline constexpr const char* kCountRowLabel = "localized correctly";
// Its label for a measure that a run localized correctly may lack (a deviation grade: a building
// built as planned has none).
inline constexpr const char* kGradedCountRowLabel = "with a number";

// A results table like the paper's Table I: one row per world, one column per method, each cell
// the APE RMSE in metres, nothing ("-") where the method failed (never localized), or "✗" where it
// was wrongly localized (eval/wrong_localization.hpp): a number would hide that.
struct ResultTable {
  std::vector<std::string> rows;                          // worlds, in first-seen order
  std::vector<std::string> columns;                       // methods, in first-seen order
  std::vector<std::vector<std::optional<double>>> cells;  // [row][column]
  std::vector<std::vector<bool>> present;                 // a run exists for the cell
  std::vector<std::vector<bool>> wrong;                   // the run was wrongly localized
  // Columns whose numbers are not localizations in B (SLAM alone, measured in its own frame):
  // their count in the last row is "n/a".
  std::vector<std::string> uncounted;
  // Per cell, when the cells aggregate several runs ([row][column]; empty: one run per cell).
  // Markdown and LaTeX then show "mean ± std k/n" (and "w✗", "f failed", "m not run"), CSV adds
  // six columns per method ("<method>: std", ": localized", ": runs", ": wrong", ": failed",
  // ": not run") that parseTableCsv skips.
  std::vector<std::vector<CellStats>> stats;
  // The last row's label: what it counts.
  std::string count_label = kCountRowLabel;

  // Sets a cell, adding its row and column when new.
  void set(const std::string& row, const std::string& column, std::optional<double> value,
           bool wrongly_localized = false);
  // Sets the statistics of a cell set before.
  void setStats(const std::string& row, const std::string& column, const CellStats& cell_stats);
  const std::optional<double>* find(const std::string& row, const std::string& column) const;
  bool isWrong(const std::string& row, const std::string& column) const;
};

enum class TableFormat { kMarkdown, kCsv, kLatex };

// The table with a last row counting, per column, the rows with a number that is not wrong
// ("n/a" for uncounted columns). LaTeX uses booktabs (\toprule, \midrule, \bottomrule), like
// the paper, with "$-$" for never localized and "$\times$" for wrong.
std::string formatTable(const ResultTable& table, TableFormat format,
                        const std::string& caption = "");

// Reads a table written as CSV (the baseline); its count row, derived from the cells, and the
// statistics columns ("<method>: std" ...) are skipped.
// Throws std::invalid_argument with the line.
ResultTable parseTableCsv(const std::string& text);

struct Regression {
  std::string row, column;
  std::optional<double> baseline, value;
  bool no_run = false;  // the baseline has the cell, the runs do not
  bool wrong = false;   // wrongly localized where the baseline was not
  std::string describe() const;
};

// Cells worse than the baseline by more than `tolerance` metres, cells that failed where the
// baseline has a number, cells wrongly localized where the baseline was not, and cells of the
// baseline with no run at all.
// `higher_is_better`: a measure where less is worse (a recall): a cell regresses when it falls
// below its baseline by more than the tolerance.
std::vector<Regression> findRegressions(const ResultTable& baseline, const ResultTable& table,
                                        double tolerance, bool higher_is_better = false);

}  // namespace isg::eval
