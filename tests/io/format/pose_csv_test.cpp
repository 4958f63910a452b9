// Tests of io/format/pose_csv: pose files with their columns in any order, the optional rx/ry/rz
// (degrees, default 0), unit-quaternion columns where the caller allows them, the timed reader's
// `t` column and the pass-through columns. Expected poses are written out by hand here; rotations
// are compared through Eigen's own AngleAxis products (R = Rz Ry Rx), independent of
// models/core/pose.
#include "io/format/pose_csv.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

constexpr double kPi = std::numbers::pi;

class PoseCsv : public scratch::ScratchDirTest {
 protected:
  // The message of reading `text` as a pose file (timed or not).
  std::string error_of(const std::string& name, const std::string& text, bool timed = false) {
    const std::string file = write(name, text);
    try {
      if (timed) {
        read_timed_pose_csv(file);
      } else {
        read_pose_csv(file);
      }
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
};

// R = Rz(rz) Ry(ry) Rx(rx), from Eigen's angle-axis rotations.
Eigen::Matrix3d zyx(double rx, double ry, double rz) {
  return (Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

TEST_F(PoseCsv, ColumnsInAnyOrderAnglesInDegreesAndOptional) {
  const PoseTable t = read_pose_csv(write("p.csv",
                                          "label,rz,z,x,y,rx\n"
                                          "home,0,0.9,0,0,0\n"
                                          "a,30,0.85,0.1,-0.2,-4.5\n"));
  ASSERT_EQ(t.poses.size(), 2u);
  EXPECT_EQ(t.columns.x, 3);
  EXPECT_EQ(t.columns.y, 4);
  EXPECT_EQ(t.columns.z, 2);
  EXPECT_EQ(t.columns.rx, 5);
  EXPECT_EQ(t.columns.ry, -1);  // absent: 0 deg
  EXPECT_EQ(t.columns.rz, 1);
  EXPECT_FALSE(t.columns.quaternion());
  EXPECT_EQ(t.poses[1].position, Eigen::Vector3d(0.1, -0.2, 0.85));
  EXPECT_EQ(t.angles_deg[1], Eigen::Vector3d(-4.5, 0.0, 30.0));  // as written
  EXPECT_NEAR(t.poses[1].angles(0), -4.5 * kPi / 180.0, 1e-15);
  EXPECT_EQ(t.poses[1].angles(1), 0.0);
  EXPECT_NEAR(t.poses[1].angles(2), kPi / 6.0, 1e-15);
  EXPECT_EQ(t.time_column, -1);
  EXPECT_TRUE(t.times.empty());

  // Without any angle column every pose has zero angles.
  const PoseTable plain = read_pose_csv(write("xyz.csv", "z,y,x\n0.9,0.02,-0.01\n"));
  ASSERT_EQ(plain.poses.size(), 1u);
  EXPECT_EQ(plain.poses[0].position, Eigen::Vector3d(-0.01, 0.02, 0.9));
  EXPECT_EQ(plain.poses[0].angles, Eigen::Vector3d::Zero());
  EXPECT_EQ(plain.angles_deg[0], Eigen::Vector3d::Zero());
}

TEST_F(PoseCsv, MissingPositionColumnAndBadCellsNameFileLineAndColumn) {
  const std::string file = path("nox.csv");
  EXPECT_EQ(error_of("nox.csv", "a,y,z\n1,2,3\n"),
            file + ":1: expected a column 'x' in the header, found 'a,y,z'");
  EXPECT_EQ(error_of("text.csv", "x,y,z\n0,0,0.9\n0,zero,0.9\n"),
            path("text.csv") + ":3: column 2 'y': expected a finite number, found 'zero'");
  EXPECT_EQ(error_of("nan.csv", "x,y,z,rx\n0,0,0.9,nan\n"),
            path("nan.csv") + ":2: column 4 'rx': expected a finite number, found 'nan'");
}

// qw,qx,qy,qz where the caller allows them: the rotation of the quaternion, its ZYX angles.
TEST_F(PoseCsv, QuaternionColumnsGiveTheRotationAndItsAngles) {
  // q = (cos(a/2), sin(a/2) n) for 90 deg about z, and for the ZYX angles (10, -20, 35) deg by
  // Eigen's quaternion product q_z q_y q_x.
  const double h = std::sqrt(0.5);
  const double rx = 10 * kPi / 180, ry = -20 * kPi / 180, rz = 35 * kPi / 180;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()));
  const std::string text = "qx,x,qz,y,z,qw,qy,id\n0,0.1," + format_number(h) + ",0.2,0.8," +
                           format_number(h) + ",0,a\n" + format_number(q.x()) + ",0," +
                           format_number(q.z()) + ",0,0.9," + format_number(q.w()) + "," +
                           format_number(q.y()) + ",b\n";
  const CsvTable table = parse_csv(text, "q.csv");
  const PoseColumns columns = find_pose_columns(table, PoseOrientation::euler_or_quaternion);
  EXPECT_TRUE(columns.quaternion());
  EXPECT_EQ(columns.qw, 5);
  EXPECT_EQ(columns.qx, 0);
  EXPECT_EQ(columns.qy, 6);
  EXPECT_EQ(columns.qz, 2);
  EXPECT_EQ(columns.rx, -1);
  EXPECT_TRUE(columns.contains(6));
  EXPECT_FALSE(columns.contains(7));  // id

  Eigen::Vector3d deg;
  const Pose yaw = pose_of_row(table, table.rows[0], columns, 1.0, &deg);
  EXPECT_EQ(yaw.position, Eigen::Vector3d(0.1, 0.2, 0.8));
  EXPECT_LT((zyx(yaw.angles(0), yaw.angles(1), yaw.angles(2)) - zyx(0, 0, kPi / 2)).norm(), 1e-12);
  EXPECT_NEAR(deg(2), 90.0, 1e-12);
  EXPECT_NEAR(deg(0), 0.0, 1e-12);
  EXPECT_NEAR(deg(1), 0.0, 1e-12);

  const Pose general = pose_of_row(table, table.rows[1], columns, 1.0, &deg);
  EXPECT_NEAR(general.angles(0), rx, 1e-12);
  EXPECT_NEAR(general.angles(1), ry, 1e-12);
  EXPECT_NEAR(general.angles(2), rz, 1e-12);
  EXPECT_NEAR(deg(0), 10.0, 1e-10);
  EXPECT_NEAR(deg(1), -20.0, 1e-10);
  EXPECT_NEAR(deg(2), 35.0, 1e-10);

  // position_scale multiplies the position only (e.g. mm in the file: 1e-3 m per unit).
  const Pose scaled = pose_of_row(table, table.rows[0], columns, 1e-3);
  EXPECT_EQ(scaled.position, Eigen::Vector3d(0.1 * 1e-3, 0.2 * 1e-3, 0.8 * 1e-3));

  // Euler-only readers treat qw.. as ordinary columns: zero angles.
  const PoseColumns euler = find_pose_columns(table);
  EXPECT_FALSE(euler.quaternion());
  EXPECT_EQ(pose_of_row(table, table.rows[1], euler).angles, Eigen::Vector3d::Zero());

  // With qw every other quaternion column is required.
  const CsvTable partial = parse_csv("x,y,z,qw,qx,qy\n0,0,0.9,1,0,0\n", "partial.csv");
  try {
    find_pose_columns(partial, PoseOrientation::euler_or_quaternion);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "partial.csv:1: expected a column 'qz' in the header, found 'x,y,z,qw,qx,qy'");
  }
}

TEST_F(PoseCsv, NonUnitQuaternionIsAnError) {
  const CsvTable table = parse_csv(
      "x,y,z,qw,qx,qy,qz\n0,0,0.9,1,0,0,0\n0,0,0.9,1.0004,0,0,0\n0,0,0.9,2,0,0,0\n", "q.csv");
  const PoseColumns columns = find_pose_columns(table, PoseOrientation::euler_or_quaternion);
  EXPECT_EQ(pose_of_row(table, table.rows[0], columns).angles, Eigen::Vector3d::Zero());
  // Within 1e-3 of norm 1 the quaternion is normalised: the identity.
  EXPECT_LT(pose_of_row(table, table.rows[1], columns).angles.norm(), 1e-15);
  try {
    pose_of_row(table, table.rows[2], columns);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "q.csv:4: columns qw,qx,qy,qz: expected a unit quaternion (norm 1 within 1e-3), "
              "found norm 2");
  }
}

TEST_F(PoseCsv, TimedReaderNeedsStrictlyIncreasingTimes) {
  const PoseTable t = read_timed_pose_csv(
      write("path.csv", "x,t,y,z,label\n0,0,0,0.7,a\n0,0.25,0,0.71,b\n0.01,0.5,0,0.72,c\n"));
  EXPECT_EQ(t.time_column, 1);
  EXPECT_EQ(t.times, (std::vector<double>{0.0, 0.25, 0.5}));
  ASSERT_EQ(t.poses.size(), 3u);
  EXPECT_EQ(t.poses[2].position, Eigen::Vector3d(0.01, 0.0, 0.72));
  EXPECT_EQ(t.other_columns(), (std::vector<int>{4}));  // t is not passed through

  // The 4th line goes back in time; the 3rd repeats the time: both name the line and column.
  EXPECT_EQ(error_of("back.csv", "t,x,y,z\n0,0,0,0.7\n0.5,0,0,0.71\n0.4,0,0,0.72\n", true),
            path("back.csv") +
                ":4: column 1 't': expected a time greater than the previous sample's 0.5, "
                "found 0.4");
  EXPECT_EQ(error_of("same.csv", "x,y,z,t\n0,0,0.7,1\n0,0,0.71,1\n", true),
            path("same.csv") +
                ":3: column 4 't': expected a time greater than the previous sample's 1, found 1");
  EXPECT_EQ(error_of("one.csv", "t,x,y,z\n0,0,0,0.7\n", true),
            path("one.csv") + ": expected at least 2 path samples, found 1");
  EXPECT_EQ(error_of("no_t.csv", "x,y,z\n0,0,0.7\n0,0,0.71\n", true),
            path("no_t.csv") + ":1: expected a column 't' in the header, found 'x,y,z'");
  // The untimed reader takes the same file with a `t` column as an ordinary column.
  const PoseTable untimed = read_pose_csv(path("back.csv"));
  EXPECT_EQ(untimed.poses.size(), 3u);
  EXPECT_EQ(untimed.other_columns(), (std::vector<int>{0}));
}

// The columns that are neither pose nor time columns, in file order, for commands to pass on.
TEST_F(PoseCsv, OtherColumnsAreTheRestInFileOrder) {
  const PoseTable t =
      read_pose_csv(write("p.csv", "id,x,note,y,ry,z,weight\n7,0,\"a,b\",0,5,0.9,2.5\n"));
  EXPECT_EQ(t.other_columns(), (std::vector<int>{0, 2, 6}));
  EXPECT_EQ(t.table.rows[0].cells[2], "a,b");
  EXPECT_NEAR(t.poses[0].angles(1), 5 * kPi / 180, 1e-15);
  EXPECT_EQ(read_pose_csv(write("q.csv", "x,y,z,rx,ry,rz\n0,0,1,0,0,0\n")).other_columns(),
            std::vector<int>{});
}

}  // namespace
}  // namespace pkmopt
