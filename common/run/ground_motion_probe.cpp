#include "common/run/ground_motion_probe.hpp"

#include <cmath>
#include <optional>

#include "common/io/probe_file.hpp"

namespace tankfsi {

nlohmann::json write_ground_motion_probe(ProgramContext& context, const GroundMotion& motion) {
  const auto& config = context.config;
  const double interval = config.real("output.probe_interval");
  const double end = config.has("end_time") ? config.real("end_time") : motion.duration();
  const auto steps = static_cast<long>(std::floor(end / interval + 1e-9));

  std::optional<ProbeFile> probe;
  if (context.log.rank() == 0)
    probe.emplace(context.folder->probes() / "ground_acceleration.csv",
                  std::vector<std::string>{"ax_m_s2", "ay_m_s2", "az_m_s2"}, config.real("output.field_interval"));
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  Eigen::Vector3d peak_time = Eigen::Vector3d::Zero();
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * interval;
    const Eigen::Vector3d a = motion.acceleration(t);
    if (probe) probe->append(t, {a.data(), 3});
    for (int c = 0; c < 3; ++c)
      if (std::abs(a[c]) > peak[c]) {
        peak[c] = std::abs(a[c]);
        peak_time[c] = t;
      }
  }
  if (probe) probe->flush();
  context.log.info("ground motion ", config.text("excitation.type"), ": peak |a| = (", peak.x(), ", ", peak.y(), ", ",
                   peak.z(), ") m/s^2 over ", end, " s");
  return {{"excitation",
           {{"type", config.text("excitation.type")},
            {"sampled_until_s", end},
            {"peak_acceleration_m_s2", {peak.x(), peak.y(), peak.z()}},
            {"peak_time_s", {peak_time.x(), peak_time.y(), peak_time.z()}}}}};
}

}  // namespace tankfsi
