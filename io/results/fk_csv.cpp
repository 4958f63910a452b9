#include "io/results/fk_csv.hpp"

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

}  // namespace pkmopt
