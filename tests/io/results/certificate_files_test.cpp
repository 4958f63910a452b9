// The files of a working-mode certificate (io/results/certificate_files.hpp) for certificates
// built by hand: the uncertified.csv text, the certificate.json fields and the summary lines.
#include "io/results/certificate_files.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

namespace {

using namespace pkmopt;

CertificateSetting setting() {
  CertificateSetting s;
  s.region = "the workspace's 2 grid cells of 40 mm";
  s.first_boxes = 2;
  s.nominal_angles_deg = Eigen::Vector3d(0, 0, 30);
  s.tilt_deg = 10;
  s.yaw_range_deg = 5;
  s.options.min_size = 0.01;
  s.seconds = 0.5;
  return s;
}

// Two cells: one certified (det J < 0), one with 3 parts left near a singular pose.
ModeCertificate not_certified() {
  ModeCertificate c;
  c.negative_boxes = 7;
  c.positive_boxes = 2;
  c.positive_fraction = 0.25;
  c.negative_fraction = 0.5;
  c.uncertified_fraction = 0.25;
  c.min_margin = 0.125;
  c.min_centre_margin = 0.25;
  c.evaluations = 12;
  UncertifiedBox u;
  u.box.position_lo = {0.0, 0.5, 1.0};
  u.box.position_hi = {0.04, 0.54, 1.04};
  u.box.theta = Interval(0.0, 10 * std::numbers::pi / 180);
  u.box.phi = Interval(0.0, std::numbers::pi);
  u.box.gamma = Interval(-5 * std::numbers::pi / 180, 5 * std::numbers::pi / 180);
  u.parts = 3;
  u.fraction = 0.5;
  u.centre_margin = 0.001;
  u.centre_sign = 1;
  c.uncertified.push_back(u);
  return c;
}

TEST(CertificateFiles, UncertifiedCsvHasOneRowPerCellInDegrees) {
  const std::string csv = uncertified_boxes_csv(not_certified());
  EXPECT_EQ(csv,
            "x_lo,x_hi,y_lo,y_hi,z_lo,z_hi,tilt_lo,tilt_hi,azimuth_lo,azimuth_hi,yaw_lo,yaw_hi,"
            "parts,uncertified_fraction,centre_margin,centre_det_sign,budget\n"
            "0,0.04,0.5,0.54,1,1.04,0,10,0,180,-5,5,3,0.5,0.001,1,0\n");
}

TEST(CertificateFiles, JsonNamesTheVerdictTheSignsAndTheSettings) {
  const nlohmann::json j = nlohmann::json::parse(certificate_json(not_certified(), setting()));
  EXPECT_FALSE(j.at("certified").get<bool>());
  EXPECT_EQ(j.at("det_j_sign").get<int>(), 0);  // both signs
  EXPECT_EQ(j.at("certified_boxes").at("det_j_positive").get<int>(), 2);
  EXPECT_EQ(j.at("certified_boxes").at("det_j_negative").get<int>(), 7);
  EXPECT_EQ(j.at("fractions").at("uncertified").get<double>(), 0.25);
  EXPECT_EQ(j.at("uncertified_first_boxes").get<int>(), 1);
  EXPECT_EQ(j.at("uncertified_parts").get<int>(), 3);
  EXPECT_EQ(j.at("uncertified_centre_margin_min").get<double>(), 0.001);
  EXPECT_EQ(j.at("certified_margin_min").get<double>(), 0.125);
  EXPECT_EQ(j.at("region").at("tilt_deg").get<double>(), 10);
  EXPECT_EQ(j.at("region").at("nominal_orientation_deg").at(2).get<double>(), 30);
  EXPECT_EQ(j.at("settings").at("min_size_m").get<double>(), 0.01);
  EXPECT_FALSE(j.at("budget_exhausted").get<bool>());
  // A region with nothing proved has no margin: null, never NaN or inf.
  ModeCertificate empty;
  const nlohmann::json e = nlohmann::json::parse(certificate_json(empty, setting()));
  EXPECT_TRUE(e.at("certified_margin_min").is_null());
  EXPECT_TRUE(e.at("centre_margin_min").is_null());
}

TEST(CertificateFiles, TextSaysTheVerdictFirst) {
  const std::string no = certificate_text(not_certified(), setting());
  EXPECT_EQ(no.rfind("certificate: NOT certified over the workspace's 2 grid cells of 40 mm", 0),
            0u)
      << no;
  EXPECT_NE(no.find("1 of 2 first boxes (25 % of the region)"), std::string::npos) << no;
  EXPECT_NE(no.find("det J > 0 on 25 % of the region and < 0 on 50 %"), std::string::npos) << no;
  ModeCertificate yes;
  yes.negative_boxes = 4;
  yes.negative_fraction = 1.0;
  yes.min_margin = 0.2;
  yes.min_centre_margin = 0.25;
  const std::string text = certificate_text(yes, setting());
  EXPECT_EQ(text.rfind("certificate: one working mode (det J < 0) over the workspace's 2 grid "
                       "cells of 40 mm times the orientation set: no parallel singularity there, "
                       "proved on 4 boxes\n",
                       0),
            0u)
      << text;
  EXPECT_NE(text.find("at least 0.2 (certified), 0.25 at the smallest box centre"),
            std::string::npos)
      << text;
}

}  // namespace
