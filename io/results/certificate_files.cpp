#include "io/results/certificate_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "io/format/csv.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {
namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// The sign all certified boxes share: 1, -1, or 0 when there are both or none.
int common_sign(const ModeCertificate& c) {
  if (c.positive_boxes > 0 && c.negative_boxes == 0) return 1;
  if (c.negative_boxes > 0 && c.positive_boxes == 0) return -1;
  return 0;
}

double smallest_uncertified_margin(const ModeCertificate& c) {
  double m = INFINITY;
  for (const UncertifiedBox& b : c.uncertified) m = std::min(m, b.centre_margin);
  return m;
}

}  // namespace

std::string certificate_json(const ModeCertificate& c, const CertificateSetting& setting) {
  nlohmann::ordered_json j;
  j["certified"] = c.certified();
  j["det_j_sign"] = common_sign(c);
  j["region"] = {{"description", setting.region},
                 {"first_boxes", setting.first_boxes},
                 {"nominal_orientation_deg",
                  {setting.nominal_angles_deg(0), setting.nominal_angles_deg(1),
                   setting.nominal_angles_deg(2)}},
                 {"tilt_deg", setting.tilt_deg},
                 {"yaw_range_deg", setting.yaw_range_deg}};
  j["settings"] = {{"min_size_m", setting.options.min_size},
                   {"min_margin", setting.options.min_margin},
                   {"max_evaluations", setting.options.max_evaluations}};
  j["certified_boxes"] = {{"det_j_positive", c.positive_boxes},
                          {"det_j_negative", c.negative_boxes}};
  j["fractions"] = {{"det_j_positive", c.positive_fraction},
                    {"det_j_negative", c.negative_fraction},
                    {"uncertified", c.uncertified_fraction}};
  j["certified_margin_min"] = number_or_null(c.min_margin);
  j["centre_margin_min"] = number_or_null(c.min_centre_margin);
  std::int64_t parts = 0;
  for (const UncertifiedBox& b : c.uncertified) parts += b.parts;
  j["uncertified_first_boxes"] = c.uncertified.size();
  j["uncertified_parts"] = parts;
  j["uncertified_centre_margin_min"] = number_or_null(smallest_uncertified_margin(c));
  j["budget_exhausted"] = std::any_of(c.uncertified.begin(), c.uncertified.end(),
                                      [](const UncertifiedBox& b) { return b.budget; });
  j["evaluations"] = c.evaluations;
  j["seconds"] = setting.seconds;
  return j.dump(2) + "\n";
}

std::string uncertified_boxes_csv(const ModeCertificate& c) {
  std::string out =
      "x_lo,x_hi,y_lo,y_hi,z_lo,z_hi,tilt_lo,tilt_hi,azimuth_lo,azimuth_hi,yaw_lo,yaw_hi,"
      "parts,uncertified_fraction,centre_margin,centre_det_sign,budget\n";
  for (const UncertifiedBox& u : c.uncertified) {
    const PoseBox& b = u.box;
    for (int k = 0; k < 3; ++k)
      out += format_number(b.position_lo(k)) + ',' + format_number(b.position_hi(k)) + ',';
    for (const Interval& i : {b.theta, b.phi, b.gamma})
      out += format_number(rad_to_deg(i.lo)) + ',' + format_number(rad_to_deg(i.hi)) + ',';
    out += fmt::format("{},{},{},{},{}\n", u.parts, format_number(u.fraction),
                       format_number(u.centre_margin), u.centre_sign, u.budget ? 1 : 0);
  }
  return out;
}

std::string certificate_text(const ModeCertificate& c, const CertificateSetting& setting) {
  std::string text;
  const auto count = static_cast<double>(c.positive_boxes + c.negative_boxes);
  if (c.certified()) {
    text += fmt::format(
        "certificate: one working mode (det J {} 0) over {} times the orientation set: no "
        "parallel singularity there, proved on {:.0f} boxes\n",
        common_sign(c) > 0 ? ">" : "<", setting.region, count);
  } else {
    text += fmt::format("certificate: NOT certified over {} times the orientation set\n",
                        setting.region);
    if (!c.uncertified.empty())
      text += fmt::format(
          "  {} of {} first boxes ({:.3g} % of the region) hold parts not proved free of "
          "singular poses; the smallest margin at their centres is {:.3g} (uncertified.csv)\n",
          c.uncertified.size(), setting.first_boxes, 100.0 * c.uncertified_fraction,
          smallest_uncertified_margin(c));
    if (c.positive_boxes > 0 && c.negative_boxes > 0)
      text += fmt::format(
          "  det J > 0 on {:.3g} % of the region and < 0 on {:.3g} %: a singular surface "
          "divides it into two working modes\n",
          100.0 * c.positive_fraction, 100.0 * c.negative_fraction);
  }
  if (count > 0)
    text += fmt::format(
        "  margin 1/||J_c^-1||_inf on the proved boxes: at least {:.3g} (certified), {:.3g} at the "
        "smallest box centre (min size {:.3g} mm, min margin {:.3g}, {} boxes evaluated, {:.3g} "
        "s)\n",
        c.min_margin, c.min_centre_margin, 1e3 * setting.options.min_size,
        setting.options.min_margin, c.evaluations, setting.seconds);
  return text;
}

}  // namespace pkmopt
