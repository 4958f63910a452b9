// Synthetic calibration measurements: a true machine drawn around the nominal one, reachable
// random poses and noisy instrument and actuator readings with gross outliers (deterministic for a
// seed).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "problems/calibration/calibration.hpp"

namespace pkmopt {
namespace {

// splitmix64 and the distributions drawn from it (bit-reproducible for a seed).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {  // Box-Muller
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  Eigen::Vector3d normal3() {
    const double a = normal(), b = normal(), c = normal();
    return {a, b, c};
  }

 private:
  std::uint64_t state_;
};

}  // namespace

// ---- Synthetic measurements -------------------------------------------------------------------

SimulatedMeasurements simulate_measurements(const HexapodDesign& nominal_design,
                                            const CalibrationVector& nominal,
                                            const CalibrationMask& perturbed,
                                            const MeasurementSimulationOptions& options) {
  Random random(options.seed);
  SimulatedMeasurements out;
  CalibrationVector truth = nominal;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (!perturbed[static_cast<std::size_t>(i)]) continue;
    double sigma = 0.0;
    if (i < kCalibrationMachineParameters) {
      const int k = i % kCalibrationLegParameters;
      sigma = k < 6 ? options.joint_sigma : (k == 6 ? options.offset_sigma : options.gain_sigma);
    } else {
      sigma = (i - kCalibrationInstrumentIndex) % 6 < 3 ? 5.0 * options.joint_sigma : 1e-3;
    }
    truth(i) += sigma * random.normal();
  }
  out.truth = truth;
  const Hexapod hexapod(calibrated_design(nominal_design, truth));
  auto data = hexapod.make_data();
  const int max_attempts = 1000 * std::max(1, options.num_poses);
  double sigma_sum = 0.0;
  for (int attempt = 0;
       attempt < max_attempts && static_cast<int>(out.true_poses.size()) < options.num_poses;
       ++attempt) {
    Pose pose;
    pose.position = {random.uniform(-options.xy_range, options.xy_range),
                     random.uniform(-options.xy_range, options.xy_range),
                     random.uniform(options.z_min, options.z_max)};
    pose.angles = {random.uniform(-options.angle_range, options.angle_range),
                   random.uniform(-options.angle_range, options.angle_range),
                   random.uniform(-options.angle_range, options.angle_range)};
    if (!hexapod.reachable(*data, pose)) continue;
    const Vec6<double> lengths = hexapod.inverse_kinematics(pose);
    CalibrationMeasurement m;
    for (int i = 0; i < 6; ++i) {
      const int leg = kCalibrationLegParameters * i;
      m.stroke(i) = (lengths(i) - truth(leg + 6)) / (1.0 + truth(leg + 7)) +
                    options.actuator_sigma * random.normal();
    }
    const Pose exact = measurement_from_tcp_pose(truth, pose);
    const double sigma =
        options.tracker_sigma + options.tracker_sigma_per_metre * exact.position.norm();
    sigma_sum += sigma;
    m.pose.position = exact.position + sigma * random.normal3();
    m.pose.angles =
        angles_from_rotation(rotation_zyx<double>(exact.angles) *
                             rotation_from_vector(options.orientation_sigma * random.normal3()));
    out.true_poses.push_back(pose);
    out.measurements.push_back(m);
  }
  if (static_cast<int>(out.measurements.size()) < options.num_poses) {
    throw CalibrationError(fmt::format(
        "could only draw {} reachable poses of {} in the sampling box; widen or move the box",
        out.measurements.size(), options.num_poses));
  }
  const int num_outliers = std::min(options.num_outliers, options.num_poses);
  while (static_cast<int>(out.outliers.size()) < num_outliers) {
    const int k = static_cast<int>(random.next() % static_cast<std::uint64_t>(options.num_poses));
    if (std::find(out.outliers.begin(), out.outliers.end(), k) != out.outliers.end()) continue;
    out.outliers.push_back(k);
    const Eigen::Vector3d direction = random.normal3().normalized();
    out.measurements[static_cast<std::size_t>(k)].pose.position +=
        options.outlier_magnitude * direction;
  }
  std::sort(out.outliers.begin(), out.outliers.end());
  out.mean_position_sigma = options.num_poses > 0 ? sigma_sum / options.num_poses : 0.0;
  return out;
}

}  // namespace pkmopt
