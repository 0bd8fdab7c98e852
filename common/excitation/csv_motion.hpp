#pragma once
// Ground motions as CSV: a header line "time_s,ax,ay,az", then one sample a
// line, time in s and accelerations in m/s^2, times strictly increasing at a
// uniform interval (to 0.1 %: a longer one is a gap in the record).
// The writer prints every number as the shortest text that reads back to the
// same double, so a written file reads back bit for bit.
#include <filesystem>

#include "common/excitation/ground_motion.hpp"

namespace tankfsi {

/// Throws ConfigError naming the file and line for a bad header, a line without
/// exactly 4 columns, a value that is not a finite number, a time not after the
/// previous one, an interval other than the first one's, or a file without samples. Blank lines are skipped.
[[nodiscard]] SampledGroundMotion read_motion_csv(const std::filesystem::path& file);

/// Throws std::runtime_error if the file cannot be written.
void write_motion_csv(const std::filesystem::path& file, const SampledGroundMotion& motion);

}  // namespace tankfsi
