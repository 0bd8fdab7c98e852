// ProbeFile: exact values, header with units, flushing by simulated time.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/io/probe_file.hpp"
#include "support/scratch_folder.hpp"

using namespace tankfsi;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}
}  // namespace

TEST_CASE("rows read back to the same doubles", "[probe]") {
  const testing::ScratchFolder folder;
  const auto path = folder.file("probe.csv");
  {
    ProbeFile probe(path, {"wave_height_m", "pressure_Pa"}, 0.1);
    const double a[] = {0.1 + 0.2, 1.0 / 3.0};
    probe.append(0.0, a);
    const double b[] = {-1e-300, 6713.25};
    probe.append(0.005, b);
  }
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == "time_s,wave_height_m,pressure_Pa");
  std::istringstream row(lines[1]);
  std::string t, h, p;
  std::getline(row, t, ',');
  std::getline(row, h, ',');
  std::getline(row, p, ',');
  CHECK(std::stod(h) == 0.1 + 0.2);
  CHECK(std::stod(p) == 1.0 / 3.0);
  CHECK(lines[2] == "0.005,-1e-300,6713.25");
}

TEST_CASE("rows reach the disk once simulated time passes the flush interval", "[probe]") {
  const testing::ScratchFolder folder;
  const auto path = folder.file("probe.csv");
  ProbeFile probe(path, {"x_m"}, 0.1);
  const double v[] = {1.0};
  probe.append(0.0, v);  // first row: flushed (nothing flushed before)
  CHECK(lines_of(path).size() == 2);
  for (int k = 1; k <= 10; ++k) probe.append(0.01 * k, v);
  // The row at t = 0.1 completes an interval since the flush at t = 0: all rows are on disk.
  CHECK(lines_of(path).size() == 12);
}

TEST_CASE("bad columns, counts and times are refused", "[probe]") {
  const testing::ScratchFolder folder;
  const auto path = folder.file("probe.csv");
  CHECK_THROWS(ProbeFile(path, {"a,b"}, 1.0));
  CHECK_THROWS(ProbeFile(path, {"time_s"}, 1.0));
  ProbeFile probe(path, {"x_m", "y_m"}, 1.0);
  const double one[] = {1.0};
  const double two[] = {1.0, 2.0};
  CHECK_THROWS(probe.append(0.0, one));
  probe.append(1.0, two);
  CHECK_THROWS(probe.append(0.5, two));
}
