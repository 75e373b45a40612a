// CatadioptricAR Core: camera trajectories (timed world-to-camera poses read from and written to
// text files) and keyframed rigid motions for scene objects and lights.
//
// Conventions (Documentation/layout-and-conventions.md): a pose is world-to-camera, p_camera = R
// p_world + t; the camera centre in the world is -R^T t. Interpolation between two poses moves the
// camera centre along a straight line and turns the rotation by slerp (the shortest rotation
// between them), both at a constant rate in time; before the first and after the last pose the end
// pose holds.
#ifndef catarTrajectory_h
#define catarTrajectory_h

#include "CameraModel.h"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace catar
{
/// The largest trajectory file LoadTrajectory reads, and the most poses a trajectory may hold.
constexpr std::uint64_t kMaxTrajectoryFileBytes = std::uint64_t(1) << 30; // 1 GiB
constexpr std::size_t kMaxTrajectoryPoses = 10000000;

struct TimedPose
{
  double time = 0.0;
  Mat4 worldToCamera = Mat4::Identity();
};

struct Trajectory
{
  std::vector<TimedPose> poses; ///< times strictly increasing
  std::string format;           ///< the file format it was read from: "tum" or "matrix"

  bool Empty() const { return this->poses.empty(); }

  /// The pose at time t: between the two poses that bracket t, the camera centre (not t of the
  /// world-to-camera matrix!) interpolated linearly and the rotation by slerp; before the first /
  /// after the last: that pose (clamped). At a pose's time exactly that pose. Returns a rigid
  /// world-to-camera matrix; the identity for an empty trajectory, the first pose for a NaN t.
  Mat4 PoseAt(double t) const;

  /// Index of the pose whose time is nearest t (the earlier of two equally near), or -1 when
  /// none is within tolerance seconds (|time - t| <= tolerance), the trajectory is empty or t is
  /// NaN.
  int IndexAt(double t, double tolerance) const;

  /// "" when the poses are usable, otherwise a sentence naming the first bad pose: a time that is
  /// not finite or not after the previous one, a matrix that is not rigid (as LoadTrajectory
  /// checks it).
  std::string Validate() const;
};

/// Reads a trajectory file. Two formats, chosen by the count of numbers on the first data line;
/// every data line must have the same count:
///  - TUM RGB-D (8 numbers): `timestamp tx ty tz qx qy qz qw`, the CAMERA-TO-WORLD pose as the TUM
///    benchmark defines it (translation = camera centre in the world, quaternion Hamilton,
///    scalar last). Converted to world-to-camera on reading.
///  - matrix (17 numbers): a timestamp and the 16 numbers of world-to-camera, row-major.
/// `#` starts a comment (whole line or rest of line); blank lines are skipped; numbers are
/// separated by spaces, tabs or commas; CRLF line ends are accepted.
///
/// Errors return false and leave `trajectory` unchanged; `error` is one sentence that names the
/// file and the 1-based line, e.g. "poses.txt line 7: expected 8 numbers (TUM: timestamp tx ty tz
/// qx qy qz qw), found 6". Refused: a wrong count, a word that is not a number, NaN/Inf or a
/// number out of a double's range, timestamps not strictly increasing, a quaternion whose norm is
/// not within 1e-3 of 1 (one that is gets normalised: many files print 4-6 digits), a matrix that
/// is not rigid (max |R^T R - I| > 1e-6, det R < 0, last row not 0 0 0 1), no poses at all, a file
/// that cannot be opened or read, a file larger than kMaxTrajectoryFileBytes, more than
/// kMaxTrajectoryPoses poses. Matrices are kept as written (not re-orthonormalised).
bool LoadTrajectory(const std::string& path, Trajectory& trajectory, std::string& error);

/// The same for text in memory; `name` stands for the file name in error messages. `maxPoses`
/// is the most poses accepted.
bool ParseTrajectory(const std::string& text, const std::string& name, Trajectory& trajectory,
  std::string& error, std::size_t maxPoses = kMaxTrajectoryPoses);

/// Writes it in the given format ("tum" or "matrix") with 17 significant digits, so that
/// LoadTrajectory reads back the same numbers (matrix: bit-exact; TUM: the same poses up to the
/// roundoff of recomputing the quaternion from the matrix, a few 1e-16 relative). A comment line
/// heads the file. Refuses an unknown format, a trajectory that Validate refuses or that is empty,
/// and text larger than kMaxTrajectoryFileBytes.
bool SaveTrajectory(const std::string& path, const Trajectory& trajectory,
  const std::string& format, std::string& error);

/// Keyframes of a rigid motion for scene objects and lights: position (vec3) and rotation (unit
/// quaternion) at times; linear interpolation of positions and slerp of rotations, clamped
/// outside, as PoseAt.
struct Keyframe
{
  double time = 0.0;
  Vec3 position = Vec3::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

struct Keyframes
{
  std::vector<Keyframe> frames; ///< times strictly increasing

  bool Empty() const { return this->frames.empty(); }

  /// Position and rotation at time t (exactly a frame's at its time; zero and identity when there
  /// are no frames; the first frame's for a NaN t).
  void At(double t, Vec3& position, Eigen::Quaterniond& rotation) const;

  /// "" or a sentence naming the first bad frame: a time not finite or not after the previous
  /// one, a position not finite, a rotation not finite or not of unit norm (within 1e-6).
  std::string Validate() const;
};
} // namespace catar

#endif
