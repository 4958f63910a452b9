#include "io/format/pose_csv.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"

namespace pkmopt {

bool PoseColumns::contains(int c) const {
  for (int k : {x, y, z, rx, ry, rz, qw, qx, qy, qz})
    if (k >= 0 && k == c) return true;
  return false;
}

PoseColumns find_pose_columns(const CsvTable& table, PoseOrientation orientation) {
  PoseColumns c;
  c.x = table.require_column("x");
  c.y = table.require_column("y");
  c.z = table.require_column("z");
  if (orientation == PoseOrientation::euler_or_quaternion && table.column("qw") >= 0) {
    c.qw = table.require_column("qw");
    c.qx = table.require_column("qx");
    c.qy = table.require_column("qy");
    c.qz = table.require_column("qz");
    return c;
  }
  c.rx = table.column("rx");
  c.ry = table.column("ry");
  c.rz = table.column("rz");
  return c;
}

Pose pose_of_row(const CsvTable& table, const CsvRow& row, const PoseColumns& c,
                 double position_scale, Eigen::Vector3d* angles_deg) {
  Pose pose;
  const int xyz[3] = {c.x, c.y, c.z};
  for (int k = 0; k < 3; ++k) {
    pose.position(k) = table.number(row, xyz[k]) * position_scale;
    if (!sane_input_length(pose.position(k)))
      throw InputError(fmt::format(
          "{}column {} {}: expected {}, found {}", location_prefix(table.file, row.line),
          xyz[k] + 1, quote_found(table.header[static_cast<std::size_t>(xyz[k])]),
          position_scale == 1.0 ? kLengthText
                                : fmt::format("a position within +-{:g} m", kMaxInputLength),
          quote_found(row.cells[static_cast<std::size_t>(xyz[k])])));
  }
  if (c.quaternion()) {
    const Eigen::Quaterniond q(table.number(row, c.qw), table.number(row, c.qx),
                               table.number(row, c.qy), table.number(row, c.qz));
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw InputError(fmt::format(
          "{}columns qw,qx,qy,qz: expected a unit quaternion (norm 1 within 1e-3), found norm {}",
          location_prefix(table.file, row.line), format_number(q.norm())));
    }
    pose.angles = angles_from_rotation(q.normalized().toRotationMatrix());
    if (angles_deg) *angles_deg = pose.angles * kRadToDeg;
    return pose;
  }
  Eigen::Vector3d deg = Eigen::Vector3d::Zero();
  if (c.rx >= 0) deg(0) = table.number(row, c.rx);
  if (c.ry >= 0) deg(1) = table.number(row, c.ry);
  if (c.rz >= 0) deg(2) = table.number(row, c.rz);
  pose.angles = deg_to_rad(deg);
  if (angles_deg) *angles_deg = deg;
  return pose;
}

std::vector<int> PoseTable::other_columns() const {
  std::vector<int> result;
  for (int c = 0; c < static_cast<int>(table.header.size()); ++c)
    if (!columns.contains(c) && c != time_column) result.push_back(c);
  return result;
}

namespace {

PoseTable read_poses(const std::string& path, bool timed, std::size_t min_rows) {
  PoseTable result;
  result.table = read_csv_file(path);
  const CsvTable& table = result.table;
  if (timed) result.time_column = table.require_column("t");
  result.columns = find_pose_columns(table);
  if (timed && table.rows.size() < min_rows) {
    throw InputError(fmt::format("{}: expected at least {} path samples, found {}", path, min_rows,
                                 table.rows.size()));
  }
  const std::size_t n = table.rows.size();
  result.poses.resize(n);
  result.angles_deg.resize(n);
  if (timed) result.times.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const CsvRow& row = table.rows[i];
    if (timed) {
      const double t = table.number(row, result.time_column);
      if (!result.times.empty() && !(t > result.times.back())) {
        throw InputError(fmt::format(
            "{}column {} 't': expected a time greater than the previous sample's {}, found {}",
            location_prefix(path, row.line), result.time_column + 1,
            format_number(result.times.back()), format_number(t)));
      }
      result.times.push_back(t);
    }
    result.poses[i] = pose_of_row(table, row, result.columns, 1.0, &result.angles_deg[i]);
  }
  return result;
}

}  // namespace

PoseTable read_pose_csv(const std::string& path) { return read_poses(path, false, 0); }

PoseTable read_timed_pose_csv(const std::string& path, std::size_t min_rows) {
  return read_poses(path, true, min_rows);
}

std::string pose_csv_text(const std::vector<Pose>& poses) {
  std::string text = "x,y,z,rx,ry,rz\n";
  for (const Pose& p : poses) {
    const Eigen::Vector3d deg = rad_to_deg(p.angles);
    text += fmt::format("{},{},{},{},{},{}\n", format_number(p.position.x()),
                        format_number(p.position.y()), format_number(p.position.z()),
                        format_number(deg.x()), format_number(deg.y()), format_number(deg.z()));
  }
  return text;
}

}  // namespace pkmopt
