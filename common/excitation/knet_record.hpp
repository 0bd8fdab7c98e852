#pragma once
// K-NET / KiK-net ASCII strong-motion records (NIED, https://www.kyoshin.bosai.go.jp):
// one file per component (.NS, .EW, .UD). 17 header lines "Key<spaces>Value",
//   Origin Time       2003/09/26 04:50:00
//   Station Code      HKD129
//   Sampling Freq(Hz) 100Hz
//   Duration Time(s)  300
//   Dir.              N-S
//   Scale Factor      7845(gal)/8223790
//   Max. Acc. (gal)   353.238
//   Last Correction   2003/09/26 04:50:11
//   Memo.
// (and the epicentre and station coordinates), then integer counts, 8 a line.
// Acceleration in gal = count * 7845 / 8223790. A record holding more than one
// second of samples fewer than its Duration Time announces is refused as truncated.
#include <filesystem>
#include <string>
#include <vector>

namespace tankfsi {

/// "7845(gal)/8223790": gal per count = numerator / denominator.
struct KnetScaleFactor {
  double numerator_gal = 1.0;
  double denominator_counts = 1.0;
  [[nodiscard]] double gal_per_count() const { return numerator_gal / denominator_counts; }
};

struct KnetHeader {
  std::string station_code;     ///< "HKD129"
  std::string direction;        ///< "N-S", "E-W" or "U-D" as written in the file
  double sampling_frequency = 100.0;  ///< Hz
  KnetScaleFactor scale_factor;
};

struct KnetRecord {
  KnetHeader header;
  /// m/s^2; sample i at record time i / sampling_frequency, pre-event mean removed.
  std::vector<double> acceleration;
};

/// Reads a record and removes the mean of its first pre_event_duration seconds
/// (at least one sample, at most the whole record): the instrument's offset,
/// which would otherwise integrate into a drifting ground velocity.
/// Throws ConfigError naming the file and line for: a header shorter than 17
/// lines, a missing or malformed Sampling Freq(Hz) or Scale Factor line, a count
/// that is not an integer, or a record without samples.
[[nodiscard]] KnetRecord read_knet_record(const std::filesystem::path& file, double pre_event_duration);

/// Writes a record in the same format (header fields not in KnetHeader get
/// neutral values); tests use it to make records with a known scale factor.
/// Throws std::runtime_error if the file cannot be written.
void write_knet_record(const std::filesystem::path& file, const KnetHeader& header,
                       const std::vector<long long>& counts);

}  // namespace tankfsi
