#include "io/results/fk_csv.hpp"

#include <cmath>

#include "io/format/csv.hpp"

namespace pkmopt {

std::string fk_csv(const FkResult& result) {
  const Eigen::Vector3d angles = rad_to_deg(result.pose.angles);
  std::string csv = "x,y,z,rx,ry,rz,converged,iterations,residual\n";
  for (int k = 0; k < 3; ++k) csv += format_number(result.pose.position(k)) + ',';
  for (int k = 0; k < 3; ++k) csv += format_number(angles(k)) + ',';
  csv += (result.converged ? "1," : "0,") + std::to_string(result.iterations) + ',' +
         format_number(result.residual) + '\n';
  return csv;
}

std::string fk_all_csv(const ForwardSolutions& solutions) {
  std::string csv = "mode,x,y,z,rx,ry,rz,residual,det_j,reachable,nearest_other,to_reference\n";
  for (std::size_t k = 0; k < solutions.real.size(); ++k) {
    const ForwardSolution& s = solutions.real[k];
    const Eigen::Vector3d angles = rad_to_deg(s.pose.angles);
    csv += std::to_string(k + 1) + ',';
    for (int i = 0; i < 3; ++i) csv += format_number(s.pose.position(i)) + ',';
    for (int i = 0; i < 3; ++i) csv += format_number(angles(i)) + ',';
    csv += format_number(s.residual) + ',' + format_number(s.jacobian_determinant) + ',' +
           (s.reachable ? "1," : "0,") +
           (std::isfinite(s.nearest_other) ? format_number(s.nearest_other) : std::string()) + ',' +
           format_number(s.to_reference) + '\n';
  }
  return csv;
}

}  // namespace pkmopt
