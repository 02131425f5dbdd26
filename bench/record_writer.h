// Writing the benchmark's reports: a command's runner returns its records,
// the command turns them into tables of formatted cells and a JSON document,
// and these functions render the tables as CSV and Markdown, write the files
// and draw the plots, the same way for every command (errtime, scale,
// throughput, scene, specialization, materials, stability).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace snh::bench {

// A table of cells already formatted for their file: one header row, then
// rows of the same length.
struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  void add_row(std::vector<std::string> cells) { rows.push_back(std::move(cells)); }
};

// The table as CSV: the header and every row, cells joined by commas (cells
// are written as given: csv_quoted where one may hold a comma), each line
// ended by a newline.
std::string csv_text(const Table& table);
// The table as Markdown: `| a | b |`, `|---|---|`, then a line per row.
std::string markdown_text(const Table& table);

// Writes `text` to `path` whole; snh::Error "cannot write <path>" when the
// file cannot be opened or written.
void write_text(const std::string& path, const std::string& text);
// The document as `dump(2)` and a newline.
void write_json(const std::string& path, const nlohmann::ordered_json& document);

// Cells. number: as a stream writes it with precision `digits` (6 is a
// stream's default); significant: the same, "-" when not finite;
// fixed_digits: `digits` after the point; csv_number: number(value, 9); thousands: 1,234,567; mebibytes: bytes / 2^20
// to three significant digits; csv_quoted: in double quotes, inner double quotes turned into single ones.
std::string number(double value, int digits);
std::string significant(double value, int digits = 3);
std::string fixed_digits(double value, int digits);
std::string csv_number(double value);
std::string thousands(long long n);
std::string mebibytes(size_t bytes);
std::string csv_quoted(std::string text);

// Runs bench/<script> with Debian's python3 (python3-matplotlib) as
// `script input out_dir`, its output on stderr. Where python3, the script
// or matplotlib is missing, a warning on stderr naming `command`, not a
// failure.
void draw_plots(const std::string& command, const std::string& script, const std::string& input,
                const std::string& out_dir);

// `text` as one single-quoted shell word.
std::string shell_quoted(const std::string& text);

}  // namespace snh::bench
