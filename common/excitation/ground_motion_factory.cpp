#include "common/excitation/ground_motion_factory.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/excitation/csv_motion.hpp"
#include "common/excitation/knet_record.hpp"
#include "common/excitation/synthetic_motion.hpp"
#include "common/io/number_text.hpp"

namespace tankfsi {

namespace {

// Numbers in messages as people write them ("10 s", "200 Hz"), not "10.000000".
std::string with_unit(double value, const char* unit) { return number_text(value) + " " + unit; }
std::string seconds(double t) { return with_unit(t, "s"); }

// Window (knet, csv only) and scales (all sampled kinds) from the case.
// Without a window the whole record is used, so simulation time 0 is the
// record's first sample.
SampledGroundMotion windowed_and_scaled(const CaseConfig& config, const SampledGroundMotion& record) {
  RecordMapping mapping = whole_record(record);
  if (config.has("excitation.window")) {
    const auto window = config.real_vector("excitation.window");
    if (window[1] <= window[0])
      throw config.error_at("excitation.window", "end " + seconds(window[1]) + " must be after start " +
                                                     seconds(window[0]));
    if (window[0] < mapping.window_start || window[1] > mapping.window_end)
      throw config.error_at("excitation.window", "[" + seconds(window[0]) + ", " + seconds(window[1]) +
                                                     "] leaves the record, which spans [" +
                                                     seconds(mapping.window_start) + ", " +
                                                     seconds(mapping.window_end) + "]");
    mapping.window_start = window[0];
    mapping.window_end = window[1];
  }
  mapping.time_scale = config.real("excitation.time_scale");
  mapping.amplitude_scale = config.real("excitation.amplitude_scale");
  return map_record(record, mapping);
}

// One K-NET file per axis (any of x, y, z; absent axes stay zero). The files of
// one station can differ by a few samples in length: all components are cut to
// the shortest, and they must share one sampling frequency so that sample i is
// the same instant in each.
SampledGroundMotion knet_record_motion(const CaseConfig& config) {
  if (!config.has("excitation.knet"))  // located at excitation.type: the absent keys have no line
    throw config.error_at("excitation.type", "knet needs at least one record file: excitation.knet.x, .y or .z");
  const std::array<std::string, 3> keys{"excitation.knet.x", "excitation.knet.y", "excitation.knet.z"};
  const double pre_event_duration = config.real("excitation.pre_event_duration");
  std::array<std::optional<KnetRecord>, 3> records;
  std::optional<std::size_t> first;
  std::size_t samples = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    if (!config.has(keys[c])) continue;
    records[c] = read_knet_record(config.path(keys[c]), pre_event_duration);
    const auto& record = *records[c];
    if (!first) {
      first = c;
      samples = record.acceleration.size();
      continue;
    }
    const double frequency = records[*first]->header.sampling_frequency;
    if (record.header.sampling_frequency != frequency)
      throw config.error_at(keys[c], "sampling frequency " + with_unit(record.header.sampling_frequency, "Hz") +
                                         " differs from " + with_unit(frequency, "Hz") + " of " + keys[*first]);
    samples = std::min(samples, record.acceleration.size());
  }
  const double frequency = records[first.value()]->header.sampling_frequency;
  std::vector<double> times(samples);
  std::vector<Eigen::Vector3d> accelerations(samples, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < samples; ++i) {
    times[i] = static_cast<double>(i) / frequency;  // not i * dt: no accumulated rounding
    for (std::size_t c = 0; c < 3; ++c)
      if (records[c]) accelerations[i][static_cast<Eigen::Index>(c)] = records[c]->acceleration[i];
  }
  return SampledGroundMotion(std::move(times), std::move(accelerations));
}

SampledGroundMotion synthetic_record(const CaseConfig& config) {
  SyntheticMotionParameters p;
  p.seed = static_cast<std::uint64_t>(config.integer("excitation.synthetic.seed"));
  p.peak_acceleration = config.real("excitation.synthetic.peak_acceleration");
  p.dominant_period = config.real("excitation.synthetic.dominant_period");
  p.ground_damping = config.real("excitation.synthetic.ground_damping");
  p.duration = config.real("excitation.synthetic.duration");
  p.rise_time = config.real("excitation.synthetic.rise_time");
  p.strong_duration = config.real("excitation.synthetic.strong_duration");
  p.component_ratios = config.vector3("excitation.synthetic.component_ratios");
  if (p.duration <= p.rise_time + p.strong_duration)
    throw config.error_at("excitation.synthetic.duration",
                          "must be longer than rise_time + strong_duration (" + seconds(p.rise_time) + " + " +
                              seconds(p.strong_duration) + "), to leave room for the decay");
  return make_synthetic_motion(p);
}

Eigen::Vector3d sine_direction(const CaseConfig& config) {
  const Eigen::Vector3d direction = config.vector3("excitation.direction");
  if (direction.norm() == 0.0) throw config.error_at("excitation.direction", "must not be the zero vector");
  return direction;
}

// The motion itself, starting at its own time 0.
std::unique_ptr<GroundMotion> unshifted_motion(const CaseConfig& config, const std::string& type) {
  auto sampled = [&](const SampledGroundMotion& record) {
    return std::make_unique<SampledGroundMotion>(windowed_and_scaled(config, record));
  };
  if (type == "knet") return sampled(knet_record_motion(config));
  if (type == "csv") return sampled(read_motion_csv(config.path("excitation.csv_file")));
  if (type == "synthetic") return sampled(synthetic_record(config));
  if (type == "harmonic")
    return std::make_unique<HarmonicGroundMotion>(sine_direction(config), config.real("excitation.amplitude"),
                                                  config.real("excitation.frequency"),
                                                  config.real("excitation.ramp_duration"));
  if (type == "sweep")
    return std::make_unique<SweepGroundMotion>(
        sine_direction(config), config.real("excitation.amplitude"), config.real("excitation.start_frequency"),
        config.real("excitation.end_frequency"), config.real("excitation.sweep_duration"),
        config.real("excitation.ramp_duration"));
  throw config.error_at("excitation.type", "unknown ground motion type '" + type + "'");
}

}  // namespace

std::unique_ptr<GroundMotion> make_ground_motion(const CaseConfig& config) {
  const std::string type = config.text("excitation.type");
  if (type == "none") return std::make_unique<ZeroGroundMotion>();
  return std::make_unique<DelayedGroundMotion>(unshifted_motion(config, type), config.real("excitation.start_time"));
}

}  // namespace tankfsi
