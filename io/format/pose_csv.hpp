// Pose CSV files: TCP poses (and optionally times) as users write them.
//
// A pose file has a header with `x,y,z` (m, base frame) and optionally the orientation as
// `rx,ry,rz` (degrees, R = Rz(rz)·Ry(ry)·Rx(rx), default 0) or, where the caller allows it, as a
// unit quaternion `qw,qx,qy,qz`; a path file also has `t` (s). Columns may come in any order;
// the other columns are kept so that commands can pass them through. Errors throw InputError
// with file, line and column (docs/conventions.md):
//   poses.csv:7: column 2 'y': expected a finite number, found 'zero'
//
// Example:
//   const PoseTable poses = read_pose_csv("poses.csv");
//   for (std::size_t i = 0; i < poses.poses.size(); ++i) machine.analyze(data, poses.poses[i], w,
//   m);
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

/// Which orientation columns a reader accepts.
enum class PoseOrientation {
  euler,                ///< rx,ry,rz (deg), each optional (default 0)
  euler_or_quaternion,  ///< rx,ry,rz or qw,qx,qy,qz (a unit quaternion within 1e-3)
};

/// Where the pose columns of a table are (-1: absent).
struct PoseColumns {
  int x = -1, y = -1, z = -1;
  int rx = -1, ry = -1, rz = -1;
  int qw = -1, qx = -1, qy = -1, qz = -1;
  bool quaternion() const { return qw >= 0; }
  /// True when column c is one of the pose columns.
  bool contains(int c) const;
};

/// The pose columns of a table; x, y, z are required (InputError naming the columns found).
/// With euler_or_quaternion and a `qw` column, qw, qx, qy, qz are all required.
PoseColumns find_pose_columns(const CsvTable& table,
                              PoseOrientation orientation = PoseOrientation::euler);

/// The pose of one row: position times `position_scale` (m per file unit), angles in radians.
/// `angles_deg` (optional) receives rx, ry, rz in degrees as given (zero for absent columns; for
/// quaternions the ZYX angles of the rotation).
Pose pose_of_row(const CsvTable& table, const CsvRow& row, const PoseColumns& columns,
                 double position_scale = 1.0, Eigen::Vector3d* angles_deg = nullptr);

/// A pose file read whole.
struct PoseTable {
  CsvTable table;                           ///< the file as read (for pass-through columns)
  PoseColumns columns;                      ///< where the pose columns are
  int time_column = -1;                     ///< `t` when times were asked for
  std::vector<Pose> poses;                  ///< one per row (radians inside)
  std::vector<Eigen::Vector3d> angles_deg;  ///< rx, ry, rz as given (degrees)
  std::vector<double> times;                ///< s, one per row when times were asked for
  /// The columns that are neither pose nor time columns, in file order.
  std::vector<int> other_columns() const;
};

/// Reads a pose file (columns x, y, z, optional rx, ry, rz).
PoseTable read_pose_csv(const std::string& path);

/// A pose file of `poses`: header `x,y,z,rx,ry,rz` (m, degrees), one row per pose, numbers that
/// read back to the same values; read_pose_csv reads it.
std::string pose_csv_text(const std::vector<Pose>& poses);

/// Reads a path file: a `t` column (s, strictly increasing, InputError naming the row
/// otherwise) and at least `min_rows` rows besides the pose columns.
PoseTable read_timed_pose_csv(const std::string& path, std::size_t min_rows = 2);

}  // namespace pkmopt
