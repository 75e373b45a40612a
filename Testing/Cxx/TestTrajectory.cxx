// Trajectories and keyframes: the TUM convention (camera-to-world, scalar-last quaternion)
// against poses built by hand, file round trips, interpolation against closed forms, every
// refused input with its line number, nearest-pose look-up, and keyframed motions.
#include "Trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace catar;
using Eigen::Quaterniond;

namespace
{
const double kPi = 3.14159265358979323846;

std::string TempPath(const std::string& name)
{
  return ::testing::TempDir() + "/catar_trajectory_" + name;
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// x with 17 significant digits (reads back exactly).
std::string Digits(double x)
{
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

/// Rodrigues' formula written out: rotation by `angle` about the unit `axis`.
Mat3 Rodrigues(const Vec3& axis, double angle)
{
  Mat3 k;
  k << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(), axis.x(), 0;
  return Mat3::Identity() + std::sin(angle) * k + (1.0 - std::cos(angle)) * k * k;
}

/// World-to-camera from a camera-to-world rotation and the camera centre.
Mat4 FromCameraToWorld(const Mat3& cameraToWorld, const Vec3& centre)
{
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = cameraToWorld.transpose();
  m.topRightCorner<3, 1>() = -cameraToWorld.transpose() * centre;
  return m;
}

double RigidityError(const Mat4& m)
{
  const Mat3 r = m.topLeftCorner<3, 3>();
  const double orthogonality = (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff();
  const double lastRow = (m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff();
  return std::max({ orthogonality, lastRow, std::abs(r.determinant() - 1.0) });
}

Vec3 Centre(const Mat4& m)
{
  return -m.topLeftCorner<3, 3>().transpose() * m.topRightCorner<3, 1>();
}

/// A random rigid world-to-camera matrix (rotation from a random axis and angle).
Mat4 RandomPose(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
  return FromCameraToWorld(
    Rodrigues(axis, kPi * (u(rng) + 1.0) / 2.0 * 0.999), Vec3(u(rng), u(rng), u(rng)) * 10.0);
}

/// A TUM line "t cx cy cz qx qy qz qw" for a rotation of `angle` about `axis` (camera-to-world).
std::string TumLine(double t, const Vec3& centre, const Vec3& axis, double angle)
{
  const Vec3 xyz = std::sin(angle / 2.0) * axis;
  return Digits(t) + " " + Digits(centre.x()) + " " + Digits(centre.y()) + " " +
    Digits(centre.z()) + " " + Digits(xyz.x()) + " " + Digits(xyz.y()) + " " + Digits(xyz.z()) +
    " " + Digits(std::cos(angle / 2.0)) + "\n";
}

Trajectory Parsed(const std::string& text)
{
  Trajectory trajectory;
  std::string error;
  EXPECT_TRUE(ParseTrajectory(text, "test.txt", trajectory, error)) << error;
  return trajectory;
}

/// The rotation angle between two rotation matrices.
double AngleBetween(const Mat3& a, const Mat3& b)
{
  const double c = ((a.transpose() * b).trace() - 1.0) / 2.0;
  return std::acos(std::clamp(c, -1.0, 1.0));
}

const std::string kIdentityTum = "0 0 0 0 0 0 0 1\n";
const std::string kRowsIdentity = "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1";
} // namespace

TEST(Trajectory, TumLineIsCameraToWorld)
{
  // 90 degrees about world z: the camera's x axis points along world +y, so the world direction
  // +y is the camera's +x and world +x is the camera's -y.
  const Vec3 centre(1.0, 2.0, 3.0);
  const Trajectory quarter =
    Parsed("5 1 2 3 0 0 " + Digits(std::sqrt(0.5)) + " " + Digits(std::sqrt(0.5)) + "\n");
  ASSERT_EQ(quarter.poses.size(), 1u);
  EXPECT_EQ(quarter.format, "tum");
  EXPECT_EQ(quarter.poses[0].time, 5.0);
  const Mat4& m = quarter.poses[0].worldToCamera;
  EXPECT_LT((m * centre.homogeneous()).head<3>().norm(), 1e-12);
  EXPECT_LT((m.topLeftCorner<3, 3>() * Vec3(0, 1, 0) - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((m.topLeftCorner<3, 3>() * Vec3(1, 0, 0) - Vec3(0, -1, 0)).norm(), 1e-12);

  // A general axis and angle: the camera's optical axis (camera +z) lies along R_cw e_z.
  const Vec3 axis = Vec3(0.3, -0.5, 0.8).normalized();
  const double angle = 1.234;
  const Vec3 c2(-0.7, 4.5, 0.25);
  const Trajectory general = Parsed("# t x y z qx qy qz qw\n" + TumLine(0.5, c2, axis, angle));
  ASSERT_EQ(general.poses.size(), 1u);
  const Mat4& g = general.poses[0].worldToCamera;
  const Mat3 cameraToWorld = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  EXPECT_LT((g * c2.homogeneous()).head<3>().norm(), 1e-12);
  EXPECT_LT(
    (g.topLeftCorner<3, 3>() * (cameraToWorld * Vec3::UnitZ()) - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_LT(
    (g.topLeftCorner<3, 3>() * (cameraToWorld * Vec3::UnitX()) - Vec3::UnitX()).norm(), 1e-12);
  EXPECT_LT(RigidityError(g), 1e-12);
}

TEST(Trajectory, MatrixFileRoundTripIsExact)
{
  std::mt19937 rng(7);
  Trajectory original;
  for (int i = 0; i < 50; ++i)
  {
    original.poses.push_back({ 1.3e9 + 0.1 * i + 1e-7 * (i % 3), RandomPose(rng) });
  }
  const std::string path = TempPath("round.matrix.txt");
  std::string error;
  ASSERT_TRUE(SaveTrajectory(path, original, "matrix", error)) << error;
  Trajectory read;
  ASSERT_TRUE(LoadTrajectory(path, read, error)) << error;
  EXPECT_EQ(read.format, "matrix");
  ASSERT_EQ(read.poses.size(), original.poses.size());
  for (std::size_t i = 0; i < read.poses.size(); ++i)
  {
    EXPECT_EQ(read.poses[i].time, original.poses[i].time);
    EXPECT_EQ(read.poses[i].worldToCamera, original.poses[i].worldToCamera) << "pose " << i;
  }
  std::remove(path.c_str());
}

TEST(Trajectory, TumFileRoundTrip)
{
  // A TUM file written by hand, read, written by SaveTrajectory and read again. The quaternion is
  // recomputed from the matrix on writing (quaternion -> matrix -> quaternion -> matrix), which
  // in double arithmetic costs a few units of roundoff: 20000 random poses gave at worst 1.3e-15
  // in a rotation entry and 1.4e-15 relative in the camera centre. So 4e-15, relative to 1 for
  // the rotation and to |c| for the centre; the matrix format is bit-exact (test above).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::string text;
  std::vector<Vec3> centres;
  std::vector<Mat3> cameraToWorld;
  for (int i = 0; i < 50; ++i)
  {
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double angle = kPi * u(rng);
    centres.push_back(Vec3(u(rng), u(rng), u(rng)) * 10.0);
    cameraToWorld.push_back(Rodrigues(axis, angle));
    text += TumLine(1.3e9 + 0.1 * i, centres.back(), axis, angle);
  }
  const std::string first = TempPath("first.tum.txt");
  const std::string second = TempPath("second.tum.txt");
  WriteText(first, text);
  Trajectory a;
  Trajectory b;
  std::string error;
  ASSERT_TRUE(LoadTrajectory(first, a, error)) << error;
  ASSERT_TRUE(SaveTrajectory(second, a, "tum", error)) << error;
  ASSERT_TRUE(LoadTrajectory(second, b, error)) << error;
  EXPECT_EQ(b.format, "tum");
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t i = 0; i < a.poses.size(); ++i)
  {
    EXPECT_EQ(a.poses[i].time, b.poses[i].time);
    const Mat4& ma = a.poses[i].worldToCamera;
    const Mat4& mb = b.poses[i].worldToCamera;
    const double length = std::max(1.0, Centre(ma).norm());
    EXPECT_LE((ma.topLeftCorner<3, 3>() - mb.topLeftCorner<3, 3>()).cwiseAbs().maxCoeff(), 4e-15)
      << "pose " << i;
    EXPECT_LE((Centre(ma) - Centre(mb)).norm(), 4e-15 * length) << "pose " << i;
    // Both against the poses the file was written from (Rodrigues: rounding of sin/cos, 1e-14).
    EXPECT_LT((Centre(mb) - centres[i]).norm(), 1e-13) << "pose " << i;
    EXPECT_LT((mb.topLeftCorner<3, 3>().transpose() - cameraToWorld[i]).norm(), 1e-14)
      << "pose " << i;
  }
  std::remove(first.c_str());
  std::remove(second.c_str());
}

TEST(Trajectory, SaveRefusesWhatCannotBeReadBack)
{
  Trajectory trajectory = Parsed(kIdentityTum);
  ASSERT_EQ(trajectory.poses.size(), 1u);
  std::string error;
  EXPECT_FALSE(SaveTrajectory(TempPath("x.txt"), trajectory, "csv", error));
  EXPECT_NE(error.find("format"), std::string::npos) << error;
  EXPECT_FALSE(SaveTrajectory(TempPath("x.txt"), Trajectory(), "tum", error));
  EXPECT_NE(error.find("no poses"), std::string::npos) << error;
  EXPECT_FALSE(SaveTrajectory(TempPath("no/such/folder/x.txt"), trajectory, "tum", error));
  trajectory.poses.push_back(trajectory.poses[0]); // same time twice
  EXPECT_FALSE(SaveTrajectory(TempPath("x.txt"), trajectory, "tum", error));
  EXPECT_NE(error.find("poses[1]"), std::string::npos) << error;
  trajectory.poses[1].time = 1.0;
  trajectory.poses[1].worldToCamera(0, 0) = 2.0;
  EXPECT_FALSE(SaveTrajectory(TempPath("x.txt"), trajectory, "matrix", error));
  EXPECT_NE(error.find("not rigid"), std::string::npos) << error;
}

TEST(Trajectory, PoseAtKeyframesMidpointsAndClamping)
{
  const Vec3 axis = Vec3(1.0, 2.0, -0.5).normalized();
  const double theta = 2.1;
  const Mat3 r0 = Rodrigues(Vec3(0, 1, 0), 0.4); // world-to-camera rotations
  const Mat3 r1 = Rodrigues(axis, theta) * r0;
  const Vec3 c0(1.0, -2.0, 0.5);
  const Vec3 c1(3.0, 4.0, -1.5);
  Trajectory trajectory;
  Mat4 m0 = Mat4::Identity();
  m0.topLeftCorner<3, 3>() = r0;
  m0.topRightCorner<3, 1>() = -r0 * c0;
  Mat4 m1 = Mat4::Identity();
  m1.topLeftCorner<3, 3>() = r1;
  m1.topRightCorner<3, 1>() = -r1 * c1;
  trajectory.poses = { { 10.0, m0 }, { 12.0, m1 } };

  EXPECT_EQ(trajectory.PoseAt(10.0), m0);
  EXPECT_EQ(trajectory.PoseAt(12.0), m1);
  EXPECT_EQ(trajectory.PoseAt(-100.0), m0);
  EXPECT_EQ(trajectory.PoseAt(9.999), m0);
  EXPECT_EQ(trajectory.PoseAt(12.001), m1);
  EXPECT_EQ(trajectory.PoseAt(1e300), m1);

  // The midpoint: half the rotation about the same axis, the centre halfway (not t halfway).
  const Mat4 mid = trajectory.PoseAt(11.0);
  EXPECT_LT((mid.topLeftCorner<3, 3>() - Rodrigues(axis, theta / 2.0) * r0).norm(), 1e-12);
  EXPECT_LT((Centre(mid) - (c0 + c1) / 2.0).norm(), 1e-12);
  const Vec3 halfT = (m0.topRightCorner<3, 1>() + m1.topRightCorner<3, 1>()) / 2.0;
  EXPECT_GT((mid.topRightCorner<3, 1>() - halfT).norm(), 0.1); // not a lerp of t
  // A quarter of the way.
  const Mat4 quarter = trajectory.PoseAt(10.5);
  EXPECT_LT((quarter.topLeftCorner<3, 3>() - Rodrigues(axis, theta / 4.0) * r0).norm(), 1e-12);
  EXPECT_LT((Centre(quarter) - (0.75 * c0 + 0.25 * c1)).norm(), 1e-12);
  EXPECT_LT(RigidityError(mid), 1e-12);

  EXPECT_EQ(trajectory.PoseAt(std::nan("")), m0);
  EXPECT_EQ(Trajectory().PoseAt(3.0), Mat4::Identity());
}

TEST(Trajectory, PoseAtIsRigidAndContinuous)
{
  std::mt19937 rng(3);
  Trajectory trajectory;
  for (int i = 0; i < 20; ++i)
  {
    trajectory.poses.push_back({ 0.5 * i, RandomPose(rng) });
  }
  std::uniform_real_distribution<double> time(-1.0, 10.5);
  for (int k = 0; k < 1000; ++k)
  {
    const double t = time(rng);
    const Mat4 m = trajectory.PoseAt(t);
    ASSERT_TRUE(m.allFinite()) << "t = " << t;
    EXPECT_LT(RigidityError(m), 1e-12) << "t = " << t;
    // Continuity: a nanosecond later the pose has barely moved (the slerp went the short way).
    const Mat4 later = trajectory.PoseAt(t + 1e-9);
    EXPECT_LT(AngleBetween(m.topLeftCorner<3, 3>(), later.topLeftCorner<3, 3>()), 1e-6);
  }
}

TEST(Trajectory, IndexAtWithTolerance)
{
  const Trajectory trajectory = Parsed("0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n2.5 0 0 0 0 0 0 1\n");
  EXPECT_EQ(trajectory.IndexAt(0.0, 0.0), 0);
  EXPECT_EQ(trajectory.IndexAt(1.0, 0.0), 1);
  EXPECT_EQ(trajectory.IndexAt(0.9, 0.2), 1);
  EXPECT_EQ(trajectory.IndexAt(0.9, 0.05), -1);
  EXPECT_EQ(trajectory.IndexAt(1.7, 0.5), -1);   // 0.7 from 1, 0.8 from 2.5
  EXPECT_EQ(trajectory.IndexAt(1.7, 0.7001), 1); // the nearer
  EXPECT_EQ(trajectory.IndexAt(2.0, 10.0), 2);   // 0.5 from 2.5, 1.0 from 1
  EXPECT_EQ(trajectory.IndexAt(1.75, 1.0), 1);   // equally near: the earlier
  EXPECT_EQ(trajectory.IndexAt(-0.25, 0.25), 0); // before the first
  EXPECT_EQ(trajectory.IndexAt(-0.25, 0.2), -1);
  EXPECT_EQ(trajectory.IndexAt(3.0, 0.5), 2); // after the last
  EXPECT_EQ(trajectory.IndexAt(3.0, 0.4), -1);
  EXPECT_EQ(trajectory.IndexAt(std::nan(""), 1e9), -1);
  EXPECT_EQ(Trajectory().IndexAt(0.0, 1e9), -1);
}

TEST(Trajectory, AcceptedSpellings)
{
  // Commas, tabs, trailing comments, CRLF line ends, a leading '+', a header comment.
  const Trajectory t =
    Parsed("# timestamp tx ty tz qx qy qz qw\r\n"
           "1.0, 0, 0, 0, 0, 0, 0, 1 # first\r\n"
           "\r\n"
           "  2.0\t+1\t0\t0\t0\t0\t0\t1\t\r\n"
           "3 0 0 0 0.1826 0.3651 0.5477 0.7303# 4 digits of (1,2,3,4)/sqrt(30)\n");
  ASSERT_EQ(t.poses.size(), 3u);
  EXPECT_EQ(t.poses[1].time, 2.0);
  EXPECT_EQ(t.poses[1].worldToCamera(0, 3), -1.0); // centre (1,0,0), identity rotation
  // The short quaternion (norm 1 - 2e-5) is normalised: a rigid matrix near the exact rotation.
  const Mat4& m = t.poses[2].worldToCamera;
  EXPECT_LT(RigidityError(m), 1e-15);
  const Mat3 exact = Eigen::Quaterniond(4, 1, 2, 3).normalized().toRotationMatrix().transpose();
  EXPECT_LT((m.topLeftCorner<3, 3>() - exact).cwiseAbs().maxCoeff(), 1e-3);
  const Trajectory matrix = Parsed("0," + kRowsIdentity + "\r\n1 " + kRowsIdentity);
  EXPECT_EQ(matrix.format, "matrix");
  EXPECT_EQ(matrix.poses.size(), 2u);
}

TEST(Trajectory, ErrorsNameTheLineAndTheProblem)
{
  const std::string tumFields = "(TUM: timestamp tx ty tz qx qy qz qw)";
  const char kBinary[] = "1 0 0 0 0 0 \0\xff 1\n"; // 8 tokens, one of them a NUL and a 0xff
  struct Case
  {
    std::string text;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
    { "", { "test.txt: no poses" } },
    { "# just a comment\n\n   # another\n", { "test.txt: no poses" } },
    { "1 2 3", { "test.txt line 1:", "expected 8 numbers", "or 17", "found 3" } },
    { "# header\n1 0 0 0 0 0 0 nan\n", { "line 2:", "'nan' is not a finite number" } },
    { "1 0 inf 0 0 0 0 1\n", { "line 1:", "'inf' is not a finite number" } },
    { "1e400 0 0 0 0 0 0 1\n", { "line 1:", "'1e400'", "out of the range" } },
    { "1 0 0 0 0 0 0 1\n1 0 x 0 0 0 0 1\n", { "line 2:", "'x' is not a number" } },
    { "1 0 0 0 0 0 0 1\n2 0 0.5.1 0 0 0 0 1\n", { "line 2:", "'0.5.1' is not a number" } },
    { "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", { "line 2:", "timestamp 1 is not after" } },
    { "2 0 0 0 0 0 0 1\n\n1 0 0 0 0 0 0 1\n", { "line 3:", "timestamp 1", "previous one (2)" } },
    { "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\n3 0 0 0 0 0 1\n",
      { "test.txt line 3: expected 8 numbers " + tumFields + ", found 7" } },
    { "0 " + kRowsIdentity + "\n1 0 0 0 0 0 0 1\n",
      { "line 2:", "expected 17 numbers (matrix", "found 8" } },
    { "1 0 0 0 0 0 0 2\n", { "line 1:", "quaternion", "norm 2", "1e-3" } },
    { "1 0 0 0 0 0 0 0\n", { "line 1:", "quaternion", "norm 0" } },
    { "1 0 0 0 0 0 0 1.01\n", { "line 1:", "norm 1.01" } },
    { "0 2 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n", { "line 1:", "not rigid", "R^T R - I" } },
    { "0 1 0 0 0 0 1 0 0 0 0 -1 0 0 0 0 1\n", { "line 1:", "not rigid", "det R < 0" } },
    { "0 1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\n", { "line 1:", "last row" } },
    { "0 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1.0000001\n", { "line 1:", "last row" } },
    { "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1 9\n", { "line 2:", "found 9" } },
    { "1 0 0 0 ,, 0 0 0 1 2\n", { "line 1:", "found 9" } },
    { std::string(kBinary, sizeof kBinary - 1), { "line 1:", "is not a number" } },
    { "1 0 0 0 0 0 0 +-1\n", { "line 1:", "'+-1' is not a number" } },
    { "1 0 0 0 0 0 0 " + std::string(100, '9') + "x\n", { "line 1:", "...' is not a number" } },
  };
  for (const Case& c : cases)
  {
    Trajectory trajectory = Parsed(kIdentityTum);
    std::string error;
    EXPECT_FALSE(ParseTrajectory(c.text, "test.txt", trajectory, error)) << c.text;
    for (const std::string& part : c.expected)
    {
      EXPECT_NE(error.find(part), std::string::npos)
        << "text: " << c.text << "\nerror: " << error << "\nmissing: " << part;
    }
    EXPECT_EQ(trajectory.poses.size(), 1u) << "a refused text leaves the trajectory unchanged";
  }
}

TEST(Trajectory, PoseCountLimit)
{
  std::string text;
  for (int i = 0; i < 4; ++i)
  {
    text += std::to_string(i) + " 0 0 0 0 0 0 1\n";
  }
  Trajectory trajectory;
  std::string error;
  EXPECT_TRUE(ParseTrajectory(text, "test.txt", trajectory, error, 4)) << error;
  EXPECT_FALSE(ParseTrajectory(text, "test.txt", trajectory, error, 3));
  EXPECT_NE(error.find("test.txt line 4: more than 3 poses"), std::string::npos) << error;
  EXPECT_EQ(kMaxTrajectoryPoses, 10000000u);
}

TEST(Trajectory, FileErrors)
{
  Trajectory trajectory;
  std::string error;
  const std::string missing = TempPath("missing.txt");
  EXPECT_FALSE(LoadTrajectory(missing, trajectory, error));
  EXPECT_NE(error.find(missing), std::string::npos) << error;
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;

  EXPECT_FALSE(LoadTrajectory(::testing::TempDir(), trajectory, error));
  EXPECT_NE(error.find("cannot"), std::string::npos) << error;

  const std::string empty = TempPath("empty.txt");
  WriteText(empty, "");
  EXPECT_FALSE(LoadTrajectory(empty, trajectory, error));
  EXPECT_NE(error.find(empty + ": no poses"), std::string::npos) << error;

  const std::string bad = TempPath("bad.txt");
  WriteText(bad, "1 0 0 0 0 0 0 1\r\n2 0 0 0 0 0 1\r\n");
  EXPECT_FALSE(LoadTrajectory(bad, trajectory, error));
  EXPECT_NE(error.find(bad + " line 2: expected 8 numbers"), std::string::npos) << error;

  // A sparse file just over 1 GiB: refused from its size, without reading it.
  const std::string huge = TempPath("huge.txt");
  WriteText(huge, "");
  std::filesystem::resize_file(huge, (std::uintmax_t(1) << 30) + 1);
  EXPECT_FALSE(LoadTrajectory(huge, trajectory, error));
  EXPECT_NE(error.find("larger than 1 GiB"), std::string::npos) << error;
  EXPECT_TRUE(trajectory.Empty());
  for (const std::string& path : { empty, bad, huge })
  {
    std::remove(path.c_str());
  }
}

TEST(Slerp, ShortWayExactEndsAndClosedForm)
{
  const Vec3 axis = Vec3(-0.2, 0.9, 0.4).normalized();
  const Quaterniond a(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
  const double theta = 1.6;
  // b = rotation of theta about `axis` after a; written out by hand as a Hamilton product.
  const Quaterniond step(std::cos(theta / 2.0), std::sin(theta / 2.0) * axis.x(),
    std::sin(theta / 2.0) * axis.y(), std::sin(theta / 2.0) * axis.z());
  const Quaterniond b = step * a;
  const Quaterniond minusB(-b.w(), -b.x(), -b.y(), -b.z());

  EXPECT_EQ(Slerp(a, b, 0.0).coeffs(), a.coeffs());
  EXPECT_EQ(Slerp(a, b, 1.0).coeffs(), b.coeffs());
  EXPECT_EQ(Slerp(a, minusB, 1.0).coeffs(), b.coeffs()); // the sign nearer a
  for (const Quaterniond& end : { b, minusB })
  {
    for (double s : { 0.25, 0.5, 0.9 })
    {
      const Mat3 expected = Rodrigues(axis, s * theta) * a.toRotationMatrix();
      const Quaterniond q = Slerp(a, end, s);
      EXPECT_LT((q.toRotationMatrix() - expected).norm(), 1e-12) << "s = " << s;
      EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    }
  }
  // The long way round would turn by 2 pi - theta: the midpoint is theta/2 from a either way.
  EXPECT_NEAR(AngleBetween(a.toRotationMatrix(), Slerp(a, minusB, 0.5).toRotationMatrix()),
    theta / 2.0, 1e-12);
}

TEST(Slerp, NearlyEqualQuaternionsGiveNoNaN)
{
  const Quaterniond a = Quaterniond(0.3, -0.4, 0.5, 0.7).normalized();
  for (double angle : { 0.0, 1e-15, 1e-9, 1e-7, 1e-6, 2e-6, 1e-3 })
  {
    const Quaterniond b = Quaterniond(Eigen::AngleAxisd(angle, Vec3::UnitY())) * a;
    const Quaterniond minusB(-b.w(), -b.x(), -b.y(), -b.z());
    for (const Quaterniond& end : { b, minusB })
    {
      for (double s : { 0.0, 1e-3, 0.5, 0.999, 1.0 })
      {
        const Quaterniond q = Slerp(a, end, s);
        ASSERT_TRUE(q.coeffs().allFinite()) << "angle " << angle << " s " << s;
        EXPECT_NEAR(q.norm(), 1.0, 1e-15);
        EXPECT_NEAR(AngleBetween(a.toRotationMatrix(), q.toRotationMatrix()), s * angle, 1e-7);
      }
    }
  }
}

TEST(Keyframe, AtInterpolatesAndClamps)
{
  const Vec3 axis = Vec3(0.0, 0.6, 0.8);
  const double theta = 2.5;
  Keyframes keyframes;
  EXPECT_TRUE(keyframes.Empty());
  Vec3 p(1, 1, 1);
  Quaterniond q(0, 1, 0, 0);
  keyframes.At(1.0, p, q);
  EXPECT_EQ(p, Vec3::Zero());
  EXPECT_EQ(q.coeffs(), Quaterniond::Identity().coeffs());

  const Quaterniond r1(
    std::cos(theta / 2.0), 0.0, std::sin(theta / 2.0) * 0.6, std::sin(theta / 2.0) * 0.8);
  keyframes.frames = { { 0.0, Vec3(0, 0, 0), Quaterniond::Identity() },
    { 2.0, Vec3(2, -4, 6), Quaterniond(-r1.w(), -r1.x(), -r1.y(), -r1.z()) },
    { 3.0, Vec3(2, -4, 7), r1 } };
  EXPECT_EQ(keyframes.Validate(), "");

  keyframes.At(2.0, p, q);
  EXPECT_EQ(p, Vec3(2, -4, 6));
  EXPECT_EQ(q.coeffs(), keyframes.frames[1].rotation.coeffs());
  keyframes.At(-5.0, p, q);
  EXPECT_EQ(p, Vec3::Zero());
  EXPECT_EQ(q.coeffs(), Quaterniond::Identity().coeffs());
  keyframes.At(std::nan(""), p, q);
  EXPECT_EQ(p, Vec3::Zero());
  EXPECT_EQ(q.coeffs(), Quaterniond::Identity().coeffs());
  keyframes.At(3.0, p, q);
  EXPECT_EQ(p, Vec3(2, -4, 7));
  EXPECT_EQ(q.coeffs(), r1.coeffs());
  keyframes.At(7.0, p, q);
  EXPECT_EQ(p, Vec3(2, -4, 7));
  EXPECT_EQ(q.coeffs(), r1.coeffs());

  keyframes.At(0.5, p, q);
  EXPECT_LT((p - Vec3(0.5, -1, 1.5)).norm(), 1e-15);
  EXPECT_LT((q.toRotationMatrix() - Rodrigues(axis, theta / 4.0)).norm(), 1e-12);
  keyframes.At(2.5, p, q); // between two signs of the same rotation: it stays still
  EXPECT_LT((p - Vec3(2, -4, 6.5)).norm(), 1e-15);
  EXPECT_LT((q.toRotationMatrix() - Rodrigues(axis, theta)).norm(), 1e-12);
}

TEST(Keyframe, ValidateNamesTheProblem)
{
  const auto expectProblem = [](const Keyframes& k, const std::string& part) {
    const std::string problem = k.Validate();
    EXPECT_NE(problem.find(part), std::string::npos) << "'" << problem << "' lacks " << part;
  };
  Keyframes k;
  EXPECT_EQ(k.Validate(), "");
  k.frames = { Keyframe{ 0.0, Vec3::Zero(), Quaterniond::Identity() },
    Keyframe{ 1.0, Vec3::Ones(), Quaterniond(Eigen::AngleAxisd(1.0, Vec3::UnitZ())) } };
  EXPECT_EQ(k.Validate(), "");

  Keyframes same = k;
  same.frames[1].time = 0.0;
  expectProblem(same, "frames[1]");
  expectProblem(same, "not after");
  Keyframes nanTime = k;
  nanTime.frames[0].time = std::nan("");
  expectProblem(nanTime, "frames[0]: the time is not finite");
  Keyframes nanPosition = k;
  nanPosition.frames[1].position.y() = std::nan("");
  expectProblem(nanPosition, "frames[1]: the position is not finite");
  Keyframes nanRotation = k;
  nanRotation.frames[1].rotation.x() = std::nan("");
  expectProblem(nanRotation, "the rotation is not finite");
  Keyframes long2 = k;
  long2.frames[1].rotation.coeffs() *= 2.0;
  expectProblem(long2, "frames[1]: the rotation quaternion's norm 2 is not 1");
  Keyframes nearlyUnit = k;
  nearlyUnit.frames[1].rotation.coeffs() *= 1.0 + 1e-9;
  EXPECT_EQ(nearlyUnit.Validate(), "");
}
