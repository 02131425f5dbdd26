// Writing the benchmark's reports: a command's runner returns its records,
// the command turns them into CSV rows, a JSON document and Markdown
// tables, and these functions write them, and draw the plots, the same way
// for every command (errtime, scale, stability).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace snh::bench {

// Writes `text` to `path` whole; snh::Error "cannot write <path>" when the
// file cannot be opened or written.
void write_text(const std::string& path, const std::string& text);
// The document as `dump(2)` and a newline.
void write_json(const std::string& path, const nlohmann::ordered_json& document);

// Runs bench/<script> with Debian's python3 (python3-matplotlib) as
// `script input out_dir`, its output on stderr. Where python3, the script
// or matplotlib is missing, a warning on stderr naming `command`, not a
// failure.
void draw_plots(const std::string& command, const std::string& script, const std::string& input,
                const std::string& out_dir);

// `text` as one single-quoted shell word.
std::string shell_quoted(const std::string& text);

}  // namespace snh::bench
