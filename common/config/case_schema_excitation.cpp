#include "common/config/case_schema.hpp"

namespace tankfsi {

// Ground motion a_g(t) in the tank-base frame: the fluid feels -a_g as a body
// force, the structure -M iota a_g. Simulation time 0 is the start of the
// motion's window (after time scaling), shifted by start_time.
std::vector<KeySpec> excitation_keys() {
  const std::vector<std::string> records{"knet", "csv"};
  const std::vector<std::string> sampled{"knet", "csv", "synthetic"};
  const std::vector<std::string> periodic{"harmonic", "sweep"};
  return {
      choice_key("excitation.type", {"none", "knet", "csv", "harmonic", "sweep", "synthetic"},
                 "Source of the ground acceleration.")
          .default_is("none"),
      input_path_key("excitation.knet.x", "K-NET ASCII record (.NS, .EW or .UD) whose motion acts along x.")
          .only_when("excitation.type", {"knet"}),
      input_path_key("excitation.knet.y", "K-NET ASCII record acting along y.").only_when("excitation.type", {"knet"}),
      input_path_key("excitation.knet.z", "K-NET ASCII record acting along z.").only_when("excitation.type", {"knet"}),
      real_key("excitation.pre_event_duration",
               "Length of the record's start over which the mean (baseline) is taken and removed.")
          .unit_is("s").default_is("5").above(0).only_when("excitation.type", {"knet"}),
      input_path_key("excitation.csv_file", "CSV file with columns time_s, ax, ay, az (m/s^2), sampled uniformly.")
          .is_required().only_when("excitation.type", {"csv"}),
      real_vector_key("excitation.window", "Part [start, end] of the record to use, in record time before scaling.")
          .unit_is("s").with_length(2).at_least(0).only_when("excitation.type", records),
      real_key("excitation.time_scale", "Factor on the record's time axis (the paper compresses time by 0.5).")
          .default_is("1").above(0).only_when("excitation.type", sampled),
      real_key("excitation.amplitude_scale", "Factor on the record's accelerations.")
          .default_is("1").at_least(0).only_when("excitation.type", sampled),
      real_vector_key("excitation.direction", "Direction of a harmonic or swept motion (normalised).")
          .with_length(3).default_is("[1, 0, 0]").only_when("excitation.type", periodic),
      real_key("excitation.amplitude", "Acceleration amplitude of a harmonic or swept motion.")
          .unit_is("m/s^2").is_required().at_least(0).only_when("excitation.type", periodic),
      real_key("excitation.frequency", "Frequency of a harmonic motion.")
          .unit_is("Hz").is_required().above(0).only_when("excitation.type", {"harmonic"}),
      real_key("excitation.start_frequency", "Frequency at the start of a linear sine sweep.")
          .unit_is("Hz").is_required().above(0).only_when("excitation.type", {"sweep"}),
      real_key("excitation.end_frequency", "Frequency at the end of a linear sine sweep.")
          .unit_is("Hz").is_required().above(0).only_when("excitation.type", {"sweep"}),
      real_key("excitation.sweep_duration", "Duration of the sine sweep; the motion stops after it.")
          .unit_is("s").is_required().above(0).only_when("excitation.type", {"sweep"}),
      real_key("excitation.ramp_duration", "Half-cosine taper at the start of a harmonic or swept motion.")
          .unit_is("s").default_is("0").at_least(0).only_when("excitation.type", periodic),
      integer_key("excitation.synthetic.seed", "Seed of the synthetic motion; equal seeds give equal motions.")
          .default_is("1").at_least(0).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.synthetic.peak_acceleration", "Largest |a| of the x component.")
          .unit_is("m/s^2").default_is("1").above(0).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.synthetic.dominant_period",
               "Period 2 pi / omega_g of the Kanai-Tajimi ground filter: where the spectrum peaks.")
          .unit_is("s").default_is("6").above(0).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.synthetic.ground_damping", "Damping ratio zeta_g of the Kanai-Tajimi filter.")
          .default_is("0.2").above(0).below(1).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.synthetic.duration", "Length of the synthetic motion.")
          .unit_is("s").default_is("60").above(0).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.synthetic.rise_time", "Envelope: quadratic rise from 0 to full amplitude.")
          .unit_is("s").default_is("5").above(0).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.synthetic.strong_duration", "Envelope: time at full amplitude before the decay.")
          .unit_is("s").default_is("20").at_least(0).only_when("excitation.type", {"synthetic"}),
      real_vector_key("excitation.synthetic.component_ratios",
                      "Amplitudes of the x, y, z components relative to x (independent phases).")
          .with_length(3).default_is("[1, 0.7, 0.5]").at_least(0).only_when("excitation.type", {"synthetic"}),
      real_key("excitation.start_time", "Simulation time at which the ground starts to move (lets the liquid settle).")
          .unit_is("s").default_is("0").at_least(0),
  };
}

}  // namespace tankfsi
