#include "common/excitation/knet_record.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "common/config/config_error.hpp"

namespace tankfsi {

namespace {

constexpr int header_line_count = 17;
constexpr double gal_to_m_per_s2 = 100.0;  // 1 gal = 1 cm/s^2 = 0.01 m/s^2: divide by 100
constexpr long long max_count = 1LL << 31;  // the largest |count| read (read_counts)

// Header keys this reader needs; the others (epicentre, times, memo) are ignored.
constexpr const char* key_station = "Station Code";
constexpr const char* key_frequency = "Sampling Freq(Hz)";
constexpr const char* key_direction = "Dir.";
constexpr const char* key_scale = "Scale Factor";
constexpr const char* key_duration = "Duration Time(s)";

std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return std::string(text.substr(first, last - first + 1));
}

// A whole token as a number of type T, or nothing (no partial reads: "12x" fails).
template <typename T>
std::optional<T> whole_number(std::string_view token) {
  T value{};
  const auto* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (token.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) return std::nullopt;
  }
  return value;
}

struct HeaderValue {
  std::string text;
  int line = 0;
};

class KnetReader {
 public:
  explicit KnetReader(const std::filesystem::path& file) : file_(file), in_(file) {
    if (!in_) fail(0, std::string("cannot read K-NET record: ") + std::strerror(errno));
  }

  KnetRecord read(double pre_event_duration) {
    read_header();
    KnetRecord record;
    record.header.station_code = optional_value(key_station);
    record.header.direction = optional_value(key_direction);
    record.header.sampling_frequency = sampling_frequency();
    record.header.scale_factor = scale_factor();
    const auto counts = read_counts();
    require_duration(counts.size(), record.header.sampling_frequency);
    record.acceleration = accelerations(counts, record.header, pre_event_duration);
    return record;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw ConfigError(Origin{file_.string(), line}, "", message);
  }

  void read_header() {
    std::string text;
    for (int n = 1; n <= header_line_count; ++n) {
      if (!std::getline(in_, text))
        fail(line_, "the header ends after " + std::to_string(line_) + " lines; a K-NET record has " +
                        std::to_string(header_line_count));
      line_ = n;
      for (const char* key : {key_station, key_frequency, key_direction, key_scale, key_duration}) {
        if (text.rfind(key, 0) == 0) header_[key] = HeaderValue{trimmed(text.substr(std::strlen(key))), n};
      }
    }
  }

  [[nodiscard]] const HeaderValue& required_value(const std::string& key) const {
    const auto it = header_.find(key);
    if (it == header_.end())
      fail(header_line_count, "the header (lines 1-" + std::to_string(header_line_count) + ") has no '" + key +
                                  "' line");
    return it->second;
  }

  [[nodiscard]] std::string optional_value(const std::string& key) const {
    const auto it = header_.find(key);
    return it == header_.end() ? "" : it->second.text;
  }

  // "100Hz"
  [[nodiscard]] double sampling_frequency() const {
    const auto& [text, line] = required_value(key_frequency);
    std::string_view number = text;
    if (number.ends_with("Hz")) number.remove_suffix(2);
    const auto value = whole_number<double>(number);
    if (!value || *value <= 0.0)
      fail(line, "malformed Sampling Freq(Hz) '" + text + "': expected a positive frequency such as 100Hz");
    return *value;
  }

  // "7845(gal)/8223790"
  [[nodiscard]] KnetScaleFactor scale_factor() const {
    const auto& [text, line] = required_value(key_scale);
    const std::string_view separator = "(gal)/";
    const auto at = text.find(separator);
    const auto numerator = at == std::string::npos ? std::nullopt
                                                   : whole_number<double>(std::string_view(text).substr(0, at));
    const auto denominator = at == std::string::npos
                                 ? std::nullopt
                                 : whole_number<double>(std::string_view(text).substr(at + separator.size()));
    if (!numerator || !denominator || *numerator <= 0.0 || *denominator <= 0.0)
      fail(line, "malformed Scale Factor '" + text + "': expected <gal>(gal)/<counts> such as 7845(gal)/8223790");
    return KnetScaleFactor{*numerator, *denominator};
  }

  std::vector<long long> read_counts() {
    std::vector<long long> counts;
    std::string text;
    while (std::getline(in_, text)) {
      ++line_;
      std::istringstream tokens(text);
      std::string token;
      while (tokens >> token) {
        const auto count = whole_number<long long>(token);
        if (!count) fail(line_, "count '" + token + "' is not an integer");
        // Loggers record 24-bit counts; 2^31 leaves room for any other and keeps
        // the pre-event sum of up to 2^31 samples inside a long long.
        if (*count > max_count || *count < -max_count)
          fail(line_, "count '" + token + "' is beyond any logger's range (|count| <= 2^31)");
        counts.push_back(*count);
      }
    }
    if (counts.empty())
      fail(line_, "no samples after the " + std::to_string(header_line_count) + " header lines");
    return counts;
  }

  // A record cut short (an interrupted download) holds fewer samples than its
  // header's Duration Time(s) announces. The announced count is allowed to
  // differ by up to one second of samples: records of one station differ by a
  // few samples in length, and the duration is often written in whole seconds.
  void require_duration(std::size_t samples, double frequency) const {
    const auto it = header_.find(key_duration);
    if (it == header_.end()) return;  // not needed to read the record
    const auto duration = whole_number<double>(it->second.text);
    if (!duration || *duration <= 0.0)
      fail(it->second.line, "malformed Duration Time(s) '" + it->second.text + "': expected a positive number of seconds");
    const double announced = *duration * frequency;
    if (static_cast<double>(samples) < announced - frequency)
      fail(line_, "truncated record: the header announces " + it->second.text + " s at " + trimmed(header_.at(key_frequency).text) +
                      " (" + std::to_string(std::llround(announced)) + " samples), the file holds " +
                      std::to_string(samples));
  }

  // The pre-event mean is taken in counts: the integer sum is exact, so the
  // offset removed does not depend on summation order or record length.
  static std::vector<double> accelerations(const std::vector<long long>& counts, const KnetHeader& header,
                                           double pre_event_duration) {
    const auto wanted = std::llround(pre_event_duration * header.sampling_frequency);
    const auto pre_event = static_cast<std::size_t>(
        std::clamp<long long>(wanted, 1, static_cast<long long>(counts.size())));
    long long sum = 0;
    for (std::size_t i = 0; i < pre_event; ++i) sum += counts[i];
    const double mean = static_cast<double>(sum) / static_cast<double>(pre_event);

    const double gal_per_count = header.scale_factor.gal_per_count();
    std::vector<double> out;
    out.reserve(counts.size());
    for (const long long count : counts)
      out.push_back((static_cast<double>(count) - mean) * gal_per_count / gal_to_m_per_s2);
    return out;
  }

  std::filesystem::path file_;
  std::ifstream in_;
  int line_ = 0;  // last line read
  std::map<std::string, HeaderValue> header_;
};

// Numbers in the header as text that reads back to the same double.
std::string exact_text(double value) {
  std::ostringstream out;
  out << std::setprecision(std::numeric_limits<double>::max_digits10) << value;
  return out.str();
}

}  // namespace

KnetRecord read_knet_record(const std::filesystem::path& file, double pre_event_duration) {
  return KnetReader(file).read(pre_event_duration);
}

void write_knet_record(const std::filesystem::path& file, const KnetHeader& header,
                       const std::vector<long long>& counts) {
  long long peak_count = 0;
  for (const long long c : counts) peak_count = std::max(peak_count, c < 0 ? -c : c);
  const double peak_gal = static_cast<double>(peak_count) * header.scale_factor.gal_per_count();
  const double duration = static_cast<double>(counts.size()) / header.sampling_frequency;

  std::ofstream out(file);
  auto line = [&](const std::string& key, const std::string& value) {
    out << std::left << std::setw(18) << key << value << '\n';
  };
  line("Origin Time", "2000/01/01 00:00:00");
  line("Lat.", "0.000");
  line("Long.", "0.000");
  line("Depth. (km)", "0");
  line("Mag.", "0.0");
  line(key_station, header.station_code);
  line("Station Lat.", "0.0000");
  line("Station Long.", "0.0000");
  line("Station Height(m)", "0");
  line("Record Time", "2000/01/01 00:00:00");
  line(key_frequency, exact_text(header.sampling_frequency) + "Hz");
  line("Duration Time(s)", exact_text(duration));
  line(key_direction, header.direction);
  line(key_scale, exact_text(header.scale_factor.numerator_gal) + "(gal)/" +
                      exact_text(header.scale_factor.denominator_counts));
  line("Max. Acc. (gal)", exact_text(peak_gal));
  line("Last Correction", "2000/01/01 00:00:00");
  out << "Memo.\n";
  for (std::size_t i = 0; i < counts.size(); ++i) out << counts[i] << (i % 8 == 7 ? '\n' : ' ');
  if (counts.size() % 8 != 0) out << '\n';
  out.close();
  if (!out) throw std::runtime_error("cannot write K-NET record " + file.string());
}

}  // namespace tankfsi
