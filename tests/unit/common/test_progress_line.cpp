// The progress line: its text, and silence when not enabled (not a terminal).
#include <catch2/catch.hpp>

#include <cstdio>

#include "common/log/progress_line.hpp"

using tankfsi::ProgressLine;

TEST_CASE("progress line text: time, share, rate and time left", "[progress]") {
  CHECK(ProgressLine::format("sph_solver", 12.4, 20.0, 1843.2, 247.0) ==
        "sph_solver  t = 12.40 / 20.00 s   62.0 %  1843 steps/s  ETA 0:04:07");
  CHECK(ProgressLine::format("fem_solver", 0.0, 20.0, 0.0, -1.0) ==
        "fem_solver  t = 0.00 / 20.00 s    0.0 %  0 steps/s  ETA --:--:--");
  CHECK(ProgressLine::format("p", 1.0, 1.0, 10.0, 3725.0).find("ETA 1:02:05") != std::string::npos);
}

TEST_CASE("progress line draws nothing when disabled", "[progress]") {
  std::FILE* sink = std::tmpfile();
  REQUIRE(sink);
  {
    ProgressLine line("prog", 1.0, false, sink);
    line.update(0.0, 0);
    line.update(0.5, 10);
    line.clear();
  }
  CHECK(std::ftell(sink) == 0);
  CHECK_FALSE(ProgressLine::on_terminal(sink));
  std::fclose(sink);
}
