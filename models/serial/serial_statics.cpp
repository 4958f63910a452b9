#include "models/serial/serial_statics.hpp"

namespace pkmopt {

Eigen::VectorXd serial_drive_loads(const FeedJacobian& Jf, const Wrench& wrench) {
  return (Jf.transpose() * wrench).array() + 0.0;
}

void add_serial_compliance(const FeedJacobian& Jf, const std::vector<SerialAxis>& axes,
                           Matrix6d& C) {
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const double k = axes[i].stiffness;
    if (k <= 0.0) continue;
    const Vector6d column = Jf.col(static_cast<Eigen::Index>(i));
    C += column * column.transpose() / k;
  }
}

}  // namespace pkmopt
