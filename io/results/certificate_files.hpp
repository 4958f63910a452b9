// The files and summary of a working-mode certificate (models/workspace/mode_certificate.hpp):
//
//   certificate_json        certificate.json: whether the region is certified, the sign of
//                           det J, the certified boxes of each sign and the fractions of the
//                           region, the certified margin, the uncertified boxes, the settings.
//   uncertified_boxes_csv   uncertified.csv, one row per first box (a workspace cell) with parts
//                           that could not be proved: x_lo,x_hi,y_lo,y_hi,z_lo,z_hi (m),
//                           tilt_lo,tilt_hi, azimuth_lo,azimuth_hi, yaw_lo,yaw_hi (deg; the
//                           orientation box about the nominal orientation,
//                           models/core/pose_box.hpp), parts (boxes left), uncertified_fraction
//                           (their share of the cell), centre_margin (the smallest at their
//                           centres), centre_det_sign (-1, 0, 1, there), budget (1: parts were
//                           left when the evaluation budget ran out).
//   certificate_text        the summary lines a command prints.
// docs/workspace.md describes every field.
//
// Example:
//   write_file_atomically("certificate.json", certificate_json(c, setting));
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "models/workspace/mode_certificate.hpp"

namespace pkmopt {

/// What was certified and how, for the files.
struct CertificateSetting {
  std::string region;  ///< in words: "the workspace's 1234 grid cells" ...
  std::int64_t first_boxes = 0;
  Eigen::Vector3d nominal_angles_deg = Eigen::Vector3d::Zero();
  double tilt_deg = 0.0;
  double yaw_range_deg = 0.0;
  CertifyOptions options;
  double seconds = 0.0;
};

std::string certificate_json(const ModeCertificate& c, const CertificateSetting& setting);
std::string uncertified_boxes_csv(const ModeCertificate& c);
/// Lines ending in newlines: the verdict, then the numbers behind it.
std::string certificate_text(const ModeCertificate& c, const CertificateSetting& setting);

}  // namespace pkmopt
