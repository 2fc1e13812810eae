#include "eval/table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace isg::eval {

namespace {

int indexOf(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

int indexOrAdd(std::vector<std::string>& names, const std::string& name) {
  const int i = indexOf(names, name);
  if (i >= 0) return i;
  names.push_back(name);
  return int(names.size()) - 1;
}

constexpr const char* kWrongMark = "✗";

// The CSV statistics columns that follow a method's column, in order.
constexpr const char* kStatsSuffixes[] = {": std",   ": localized", ": runs",
                                          ": wrong", ": failed",    ": not run"};
constexpr int kStatsColumns = int(std::size(kStatsSuffixes));

bool isStatsColumn(const std::string& header) {
  for (const char* suffix : kStatsSuffixes) {
    const std::string s = suffix;
    if (header.size() > s.size() && header.compare(header.size() - s.size(), s.size(), s) == 0) {
      return true;
    }
  }
  return false;
}

// Three decimals, every digit before them: the largest double has 309 (a fixed buffer cut them).
std::string cell(const std::optional<double>& value) {
  if (!value) return "-";
  const int size = std::snprintf(nullptr, 0, "%.3f", *value);
  std::string text(std::size_t(size) + 1, '\0');
  std::snprintf(text.data(), text.size(), "%.3f", *value);
  text.resize(std::size_t(size));
  return text;
}

// One CSV line's fields (RFC 4180): a field in double quotes may hold commas and doubled quotes;
// spaces around an unquoted field are dropped.
std::vector<std::string> splitCsv(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> out;
  std::size_t i = 0;
  while (true) {
    std::string field;
    while (i < line.size() && line[i] == ' ') ++i;
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (i < line.size()) {
        if (line[i] == '"' && i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          i += 2;
        } else if (line[i] == '"') {
          ++i;
          break;
        } else {
          field += line[i++];
        }
      }
      while (i < line.size() && line[i] != ',') ++i;
    } else {
      while (i < line.size() && line[i] != ',') field += line[i++];
      while (!field.empty() && field.back() == ' ') field.pop_back();
    }
    out.push_back(field);
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return out;
}

// A CSV field, quoted when it holds a comma, a quote or surrounding spaces; line breaks, which
// would split the row, become spaces.
std::string csvField(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  const bool quote = text.find_first_of(",\"") != std::string::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!quote) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Markdown table cells: '|' would end the cell, a line break the row.
std::string markdownCell(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else {
      out += (c == '\n' || c == '\r') ? ' ' : c;
    }
  }
  return out;
}

std::string capitalised(std::string text) {
  if (!text.empty()) text[0] = char(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}

std::string latexEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '_':
      case '&':
      case '%':
      case '#':
      case '$':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '\n':
      case '\r':
        out += ' ';
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A caption in LaTeX: escaped, with the table's marks as the cells write them ("✗" → $\times$,
// a lone "-" → $-$).
std::string latexCaption(const std::string& caption) {
  std::string text = latexEscape(caption);
  const auto replace = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos;
         at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  };
  replace(kWrongMark, "$\\times$");
  replace(" - ", " $-$ ");
  return text;
}

std::string statsCell(const CellStats& s, bool latex) {
  std::string text;
  if (s.mean) {
    text = cell(s.mean);
    if (s.std) text += (latex ? " $\\pm$ " : " ± ") + cell(s.std);
    text += " ";
  }
  text += std::to_string(s.localized) + "/" + std::to_string(s.runs);
  if (s.wrong > 0) text += " " + std::to_string(s.wrong) + (latex ? "$\\times$" : kWrongMark);
  if (s.failed > 0) text += ", " + std::to_string(s.failed) + " failed";
  if (s.not_run > 0) text += ", " + std::to_string(s.not_run) + " not run";
  return text;
}

}  // namespace

CellStats cellStats(const std::vector<std::optional<double>>& values,
                    const std::vector<bool>& wrong) {
  CellStats s;
  s.runs = int(values.size());
  std::vector<double> correct;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const bool is_wrong = i < wrong.size() && wrong[i];
    s.wrong += is_wrong;
    if (values[i] && !is_wrong) correct.push_back(*values[i]);
  }
  s.localized = int(correct.size());
  if (correct.empty()) return s;
  // Values near the largest double would overflow a plain sum to inf: then the sums are taken of
  // the values divided by the largest magnitude (any finite input gives a finite mean).
  double scale = 1.0;
  double sum = 0.0;
  for (double v : correct) sum += v;
  if (!std::isfinite(sum)) {
    scale = 0.0;
    for (double v : correct) scale = std::max(scale, std::abs(v));
    sum = 0.0;
    for (double v : correct) sum += v / scale;
  }
  const double mean = sum / double(correct.size());
  s.mean = mean * scale;
  if (correct.size() >= 2) {
    double squares = 0.0;
    for (double v : correct) squares += (v / scale - mean) * (v / scale - mean);
    if (!std::isfinite(squares) && scale == 1.0) {
      for (double v : correct) scale = std::max(scale, std::abs(v));
      const double scaled_mean = mean / scale;
      squares = 0.0;
      for (double v : correct) squares += (v / scale - scaled_mean) * (v / scale - scaled_mean);
    }
    s.std = std::sqrt(squares / double(correct.size() - 1)) * scale;
  }
  return s;
}

void ResultTable::setStats(const std::string& row, const std::string& column,
                           const CellStats& cell_stats) {
  const int r = indexOf(rows, row);
  const int c = indexOf(columns, column);
  if (r < 0 || c < 0)
    throw std::logic_error("setStats: the cell " + row + " / " + column + " is not set");
  stats.resize(rows.size());
  for (auto& line : stats) line.resize(columns.size());
  stats[r][c] = cell_stats;
}

void ResultTable::set(const std::string& row, const std::string& column,
                      std::optional<double> value, bool wrongly_localized) {
  const int r = indexOrAdd(rows, row);
  const int c = indexOrAdd(columns, column);
  cells.resize(rows.size());
  present.resize(rows.size());
  wrong.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    cells[i].resize(columns.size());
    present[i].resize(columns.size(), false);
    wrong[i].resize(columns.size(), false);
  }
  cells[r][c] = value;
  present[r][c] = true;
  wrong[r][c] = wrongly_localized;
}

bool ResultTable::isWrong(const std::string& row, const std::string& column) const {
  const int r = indexOf(rows, row);
  const int c = indexOf(columns, column);
  return r >= 0 && c >= 0 && present[r][c] && wrong[r][c];
}

const std::optional<double>* ResultTable::find(const std::string& row,
                                               const std::string& column) const {
  const int r = indexOf(rows, row);
  const int c = indexOf(columns, column);
  if (r < 0 || c < 0 || !present[r][c]) return nullptr;
  return &cells[r][c];
}

namespace {

// The text of a table's cells and lines in one format (formatTable).
class TableText {
 public:
  TableText(const ResultTable& table, TableFormat format)
      : table_(table), format_(format), with_stats_(!table.stats.empty()) {}

  std::string csv() {
    // With statistics, each method's column is followed by its statistics columns.
    line(
        "world",
        [&](std::size_t c) {
          return withStats(
              c, [&](std::size_t i) { return csvField(header(i)); },
              [&](std::size_t i, int k) {
                return csvField(header(i) + std::string(kStatsSuffixes[k]));
              });
        },
        "", ",", "");
    for (std::size_t r = 0; r < table_.rows.size(); ++r) {
      line(
          csvField(table_.rows[r]),
          [&](std::size_t c) {
            return withStats(
                c, [&](std::size_t i) { return text(r, i); },
                [&](std::size_t i, int k) { return statsField(r, i, k); });
          },
          "", ",", "");
    }
    line(
        table_.count_label,
        [&](std::size_t c) {
          return withStats(
              c, [&](std::size_t i) { return count(i); }, [](std::size_t, int) { return ""; });
        },
        "", ",", "");
    return out_.str();
  }

  std::string markdown(const std::string& caption) {
    if (!caption.empty()) out_ << caption << "\n\n";
    line(
        "world", [&](std::size_t c) { return markdownCell(header(c)); }, "| ", " | ", " |");
    line(
        "---", [](std::size_t) { return std::string("---:"); }, "|", "|", "|");
    for (std::size_t r = 0; r < table_.rows.size(); ++r) {
      line(
          markdownCell(table_.rows[r]), [&](std::size_t c) { return text(r, c); }, "| ", " | ",
          " |");
    }
    line(
        "*" + table_.count_label + "*", [&](std::size_t c) { return count(c); }, "| ", " | ", " |");
    return out_.str();
  }

  std::string latex(const std::string& caption) {
    out_ << "% needs \\usepackage{booktabs}\n\\begin{table}\n\\centering\n";
    if (!caption.empty()) out_ << "\\caption{" << latexCaption(caption) << "}\n";
    out_ << "\\begin{tabular}{l" << std::string(table_.columns.size(), 'c') << "}\n\\toprule\n";
    line(
        "World", [&](std::size_t c) { return latexEscape(header(c)); }, "", " & ", " \\\\");
    out_ << "\\midrule\n";
    for (std::size_t r = 0; r < table_.rows.size(); ++r) {
      line(
          latexEscape(table_.rows[r]), [&](std::size_t c) { return text(r, c); }, "", " & ",
          " \\\\");
    }
    out_ << "\\midrule\n";
    line(
        latexEscape(capitalised(table_.count_label)), [&](std::size_t c) { return count(c); }, "",
        " & ", " \\\\");
    out_ << "\\bottomrule\n\\end{tabular}\n\\end{table}\n";
    return out_.str();
  }

 private:
  CellStats statsOf(std::size_t r, std::size_t c) const {
    return r < table_.stats.size() && c < table_.stats[r].size() ? table_.stats[r][c] : CellStats{};
  }
  const std::string& header(std::size_t c) const { return table_.columns[c]; }
  std::string text(std::size_t r, std::size_t c) const {
    const bool latex = format_ == TableFormat::kLatex;
    if (!table_.present[r][c]) return "";
    if (with_stats_ && format_ != TableFormat::kCsv) return statsCell(statsOf(r, c), latex);
    if (table_.wrong[r][c]) return latex ? "$\\times$" : kWrongMark;
    if (latex && !table_.cells[r][c]) return "$-$";
    return cell(table_.cells[r][c]);
  }
  // The last row: per column, the rows localized correctly ("n/a" for uncounted columns).
  std::string count(std::size_t c) const {
    if (indexOf(table_.uncounted, table_.columns[c]) >= 0) return "n/a";
    int n = 0;
    for (std::size_t r = 0; r < table_.rows.size(); ++r) {
      n += table_.present[r][c] && !table_.wrong[r][c] && table_.cells[r][c].has_value();
    }
    return std::to_string(n) + "/" + std::to_string(table_.rows.size());
  }
  // CSV's statistics column k of a cell: the std, then localized, runs, wrong, failed, not run.
  std::string statsField(std::size_t r, std::size_t c, int k) const {
    if (!table_.present[r][c]) return "";
    const CellStats s = statsOf(r, c);
    if (k == 0) return s.std ? cell(s.std) : "";
    const int counts[] = {0, s.localized, s.runs, s.wrong, s.failed, s.not_run};
    return std::to_string(counts[k]);
  }
  template <typename Main, typename Extra>
  std::string withStats(std::size_t c, const Main& main, const Extra& extra) const {
    std::string fields = main(c);
    if (!with_stats_) return fields;
    for (int k = 0; k < kStatsColumns; ++k) fields += "," + std::string(extra(c, k));
    return fields;
  }
  // One line of any format: the row's label, then its cells.
  template <typename Field>
  void line(const std::string& label, const Field& field, const char* open, const char* separator,
            const char* close) {
    out_ << open << label;
    for (std::size_t c = 0; c < table_.columns.size(); ++c) out_ << separator << field(c);
    out_ << close << "\n";
  }

  const ResultTable& table_;
  TableFormat format_;
  bool with_stats_;
  std::ostringstream out_;
};

}  // namespace

std::string formatTable(const ResultTable& table, TableFormat format, const std::string& caption) {
  TableText text(table, format);
  switch (format) {
    case TableFormat::kCsv:
      return text.csv();
    case TableFormat::kMarkdown:
      return text.markdown(caption);
    case TableFormat::kLatex:
      return text.latex(caption);
  }
  return "";
}

ResultTable parseTableCsv(const std::string& text) {
  ResultTable table;
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    const auto fields = splitCsv(line);
    // Names are text: a control character (a quoted line break, a NUL) in a world or method name
    // would be written back as something else, and the baseline would name a cell no run has.
    for (const std::string& field : fields) {
      const auto control = std::find_if(field.begin(), field.end(), [](char c) {
        return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
      });
      if (control != field.end()) {
        throw std::invalid_argument("line " + std::to_string(number) +
                                    ": a control character in a field");
      }
    }
    if (header.empty()) {
      // A header of "world" alone is a table without methods, as formatTable writes it.
      if (fields[0] != "world") {
        throw std::invalid_argument("line " + std::to_string(number) +
                                    ": expected a header \"world,<method>,...\"");
      }
      header = fields;
      continue;
    }
    // Derived from the cells above it.
    if (fields[0] == kCountRowLabel || fields[0] == kGradedCountRowLabel) continue;
    if (fields.size() != header.size()) {
      throw std::invalid_argument("line " + std::to_string(number) + ": " +
                                  std::to_string(fields.size()) + " fields, the header has " +
                                  std::to_string(header.size()));
    }
    for (std::size_t c = 1; c < fields.size(); ++c) {
      if (fields[c].empty()) continue;         // no run for this cell
      if (isStatsColumn(header[c])) continue;  // derived from the runs, not compared
      if (fields[c] == "-") {
        table.set(fields[0], header[c], std::nullopt);
        continue;
      }
      if (fields[c] == kWrongMark) {
        table.set(fields[0], header[c], std::nullopt, true);
        continue;
      }
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(fields[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != fields[c].size()) {
        throw std::invalid_argument("line " + std::to_string(number) + ": \"" + fields[c] +
                                    "\" is neither a number, \"-\" nor \"" + kWrongMark + "\"");
      }
      // Every measure of a table is a finite amount >= 0: a nan or inf baseline would never
      // compare worse, and the regression gate could never fail.
      if (!std::isfinite(value) || value < 0.0) {
        throw std::invalid_argument("line " + std::to_string(number) + ", " + header[c] + ": \"" +
                                    fields[c] + "\" is not a finite number >= 0");
      }
      table.set(fields[0], header[c], value);
    }
  }
  if (header.empty()) throw std::invalid_argument("empty: expected a header \"world,...\"");
  return table;
}

std::string Regression::describe() const {
  std::string text = row + " / " + column + ": ";
  if (no_run) return text + "no run (baseline " + cell(baseline) + ")";
  if (wrong) return text + "wrongly localized (baseline " + cell(baseline) + ")";
  if (!value && baseline) return text + "failed (baseline " + cell(baseline) + ")";
  if (!value && !baseline) return text + "no run (baseline -)";
  return text + cell(value) + " m, baseline " + cell(baseline) + " m";
}

std::vector<Regression> findRegressions(const ResultTable& baseline, const ResultTable& table,
                                        double tolerance, bool higher_is_better) {
  std::vector<Regression> out;
  for (std::size_t r = 0; r < baseline.rows.size(); ++r) {
    for (std::size_t c = 0; c < baseline.columns.size(); ++c) {
      if (!baseline.present[r][c]) continue;
      const auto& expected = baseline.cells[r][c];
      const auto* got = table.find(baseline.rows[r], baseline.columns[c]);
      if (got == nullptr) {
        out.push_back({baseline.rows[r], baseline.columns[c], expected, std::nullopt, true});
        continue;
      }
      const bool baseline_wrong = baseline.wrong[r][c];
      if (table.isWrong(baseline.rows[r], baseline.columns[c])) {
        if (!baseline_wrong) {
          out.push_back({baseline.rows[r], baseline.columns[c], expected, *got, false, true});
        }
        continue;
      }
      const bool worse = !baseline_wrong && expected &&
                         (!*got || (higher_is_better ? **got < *expected - tolerance
                                                     : **got > *expected + tolerance));
      if (worse) out.push_back({baseline.rows[r], baseline.columns[c], expected, *got, false});
    }
  }
  return out;
}

}  // namespace isg::eval
