// `snh-gpu-bench throughput` at a tiny size, run as a user would: the
// roofline's square-root and division rates, and the recomputing product's
// counts and FMA-peak ceiling in the JSON, CSV and Markdown.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace snh::test {
namespace {

int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool positive(const nlohmann::json& v) {
  return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() > 0;
}

TEST(ThroughputCommand, RooflineHasSlowOperationRatesAndRecomputeItsCeiling) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_throughput_test";
  std::filesystem::remove_all(out);
  ASSERT_EQ(run_command(std::string(SNH_BENCH_BINARY) +
                        " throughput --element hex8,tet4 --precision double,float --size 2 --variant "
                        "recompute,cached,cached-float-products "
                        "--no-host-baseline --min-seconds 0.01 --out " +
                        out.string() + " > /dev/null 2>&1"),
            0);
  std::ifstream file(out / "throughput.json");
  ASSERT_TRUE(file.good());
  const nlohmann::json report = nlohmann::json::parse(file);
  for (const std::string p : {"double", "float"}) {
    const nlohmann::json& roof = report.at("roofline").at(p);
    for (const char* key :
         {"sqrt_vector_gop_s", "div_vector_gop_s", "sqrt_div_vector_gop_s", "fma_peak_vector_gflop_s"})
      EXPECT_TRUE(positive(roof.at(key))) << p << " " << key << ": " << roof.at(key);
  }
  int recompute_rows = 0, cached_rows = 0;
  std::map<std::string, double> cached_bytes;  // "<element> <precision> <variant>"
  for (const nlohmann::json& row : report.at("products")) {
    const std::string variant = row.at("variant"), precision = row.at("precision");
    if (variant != "recompute")
      cached_bytes[row.at("element_type").get<std::string>() + " " + precision + " " + variant] =
          row.at("bytes_per_element").get<double>();
    const double points = row.at("element_type") == "hex8" ? 8 : 1;
    const double ceiling = row.at("peak_ceiling");
    // The lanes program's width of the material kernels on CPUs, the scalar
    // kernels (0) on GPUs.
    const int lanes = row.at("material_lanes");
    if (report.at("device_is_gpu").get<bool>())
      EXPECT_EQ(lanes, 0);
    else
      EXPECT_TRUE(lanes == 8 || lanes == 16) << lanes;
    if (variant == "recompute") {
      ++recompute_rows;
      // Counted in the compiled linearization (bench/throughput.cpp).
      EXPECT_EQ(row.at("sqrts_per_element").get<double>(), 38 * points);
      EXPECT_EQ(row.at("divisions_per_element").get<double>(), (precision == "double" ? 41 : 40) * points);
      EXPECT_GT(ceiling, 0.0);
      EXPECT_LE(ceiling, 1.0);
      // Its measured fraction of the FMA peak cannot exceed the ceiling
      // by more than the noise of two separate timings.
      EXPECT_LE(row.at("fraction_of_peak").get<double>(), 2.0 * ceiling) << row;
    } else {
      ++cached_rows;
      EXPECT_EQ(row.at("sqrts_per_element").get<double>(), 0.0);
      EXPECT_EQ(row.at("divisions_per_element").get<double>(), 0.0);
      EXPECT_EQ(ceiling, 1.0);
    }
  }
  EXPECT_EQ(recompute_rows, 4);
  // cached in both precisions, cached-float-products in double only.
  EXPECT_EQ(cached_rows, 6);
  EXPECT_EQ(cached_bytes.count("hex8 float cached-float-products"), 0u);
  for (const std::string element : {"hex8", "tet4"}) {
    // Float cache and double vectors: between the two precisions' cached product.
    const double mixed = cached_bytes.at(element + " double cached-float-products");
    EXPECT_LT(mixed, cached_bytes.at(element + " double cached"));
    EXPECT_GT(mixed, cached_bytes.at(element + " float cached"));
  }

  std::ifstream csv(out / "throughput.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "element_type,precision,size,elements,dofs,variant,product_seconds,elements_per_second,setup_seconds,"
            "assembly_seconds,memory_bytes,flops_per_element,bytes_per_element,fraction_of_peak,fraction_of_bandwidth,"
            "sqrts_per_element,divisions_per_element,peak_ceiling");
  std::ifstream md(out / "throughput.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("| sqrt 8-wide G/s | div 8-wide G/s | sqrt+div 8-wide G/s |"), std::string::npos);
  EXPECT_NE(text.str().find("| % bandwidth | % peak ceiling |"), std::string::npos);
  std::filesystem::remove_all(out);
}

TEST(ThroughputCommand, MaterialLanesAreChosenOrRefused) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_throughput_lanes_test";
  std::filesystem::remove_all(out);
  const std::string command = std::string(SNH_BENCH_BINARY) +
                              " throughput --element hex8,tet4 --precision float --size 2 --variant recompute "
                              "--no-host-baseline --min-seconds 0.01 --out " +
                              out.string();
  EXPECT_NE(run_command(command + " --material-lanes 12 > /dev/null 2>&1"), 0);
  const int status = run_command(command + " --material-lanes 8 > /dev/null 2>&1");
  std::ifstream file(out / "throughput.json");
  if (!file.good()) {
    // Refused where the device runs the scalar kernels (GPUs), with an error.
    EXPECT_NE(status, 0);
    GTEST_SKIP() << "--material-lanes: the lanes program runs on CPU devices only";
  }
  ASSERT_EQ(status, 0);
  const nlohmann::json report = nlohmann::json::parse(file);
  ASSERT_EQ(report.at("products").size(), 2u);
  for (const nlohmann::json& row : report.at("products")) EXPECT_EQ(row.at("material_lanes"), 8) << row;
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace snh::test
