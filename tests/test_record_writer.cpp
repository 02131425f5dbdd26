// The benchmark's one writer: tables rendered as CSV and Markdown, the cell
// formats, and scale's files byte for byte as they were before its tables
// went through the writer (tests/data/records, written from the same
// records by the earlier writer; since then extended only by the fields
// added later: the profile's traffic by phase in the records, and the
// launches and read-backs per CG and per Newton iteration).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "record_writer.h"
#include "scale.h"
#include "snh/error.h"
#include "support/scale_records.h"

namespace snh::test {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(RecordWriter, TablesAsCsvAndMarkdown) {
  bench::Table t;
  t.columns = {"scene", "res", "skipped"};
  t.add_row({"twist", "3", ""});
  t.add_row({"stretch", "4", bench::csv_quoted("a \"b\", c")});
  EXPECT_EQ(bench::csv_text(t), "scene,res,skipped\ntwist,3,\nstretch,4,\"a 'b', c\"\n");
  bench::Table m;
  m.columns = {"a", "b"};
  m.add_row({"1", ""});
  EXPECT_EQ(bench::markdown_text(m), "| a | b |\n|---|---|\n| 1 |  |\n");
  m.rows.clear();
  EXPECT_EQ(bench::markdown_text(m), "| a | b |\n|---|---|\n");
}

TEST(RecordWriter, CellFormats) {
  EXPECT_EQ(bench::significant(0.123456), "0.123");
  EXPECT_EQ(bench::significant(std::nan(""), 2), "-");
  EXPECT_EQ(bench::significant(std::numeric_limits<double>::infinity()), "-");
  EXPECT_EQ(bench::number(std::numeric_limits<double>::infinity(), 6), "inf");
  EXPECT_EQ(bench::number(1234.5, 3), "1.23e+03");
  EXPECT_EQ(bench::csv_number(1.0 / 3.0), "0.333333333");
  EXPECT_EQ(bench::fixed_digits(2.0, 2), "2.00");
  EXPECT_EQ(bench::thousands(969111), "969,111");
  EXPECT_EQ(bench::thousands(-1234), "-1,234");
  EXPECT_EQ(bench::thousands(100), "100");
  EXPECT_EQ(bench::mebibytes(3 * 1024 * 1024 / 2), "1.5");
}

TEST(RecordWriter, ScaleFilesAreByteForByteAsBefore) {
  bench::ScaleOptions o;
  o.out_dir = (std::filesystem::temp_directory_path() / "snh_record_writer_scale").string();
  o.plots = false;
  std::filesystem::remove_all(o.out_dir);
  bench::write_scale(o, sample_scale_records());
  const std::filesystem::path golden = std::filesystem::path(SNH_SOURCE_DIR) / "tests/data/records";
  for (const char* file : {"scale.csv", "scale.md", "scale.json"})
    EXPECT_EQ(read_file(std::filesystem::path(o.out_dir) / file), read_file(golden / file)) << file;
}

TEST(RecordWriter, UnwritableFileNamesThePath) {
  const std::string path = "/nonexistent-folder/scale.csv";
  try {
    bench::write_text(path, "x");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace snh::test
