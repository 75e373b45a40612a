#include "Trajectory.h"

#include "FileOutput.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>
#include <utility>

namespace catar
{
namespace
{
constexpr double kRigidTolerance = 1e-6;      // max |R^T R - I| of a world-to-camera matrix
constexpr double kQuaternionTolerance = 1e-3; // | |q| - 1 | of a TUM quaternion
constexpr double kUnitTolerance = 1e-6;       // | |q| - 1 | of a keyframe rotation

const char* const kTumFields = "TUM: timestamp tx ty tz qx qy qz qw";
const char* const kMatrixFields = "matrix: timestamp and 16 numbers of world-to-camera, row-major";

/// The shortest text that reads back as v, for messages.
std::string Number(double v)
{
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

/// v with 17 significant digits, independent of the C locale.
void AppendNumber(std::string& out, double v)
{
  char buffer[32];
  const auto result =
    std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 17);
  out.append(buffer, result.ptr);
}

/// A token for an error message, quoted and cut short.
std::string Quoted(std::string_view token)
{
  constexpr std::size_t kShown = 24;
  return "'" + std::string(token.substr(0, kShown)) + (token.size() > kShown ? "...'" : "'");
}

/// Where t lies among items sorted by strictly increasing `time`: the index i of the item at or
/// before t and the fraction s of the way to item i+1. At or before the first item (or NaN t):
/// {0, 0}; at or after the last: {last, 0}. Items must not be empty.
template<class Item>
std::pair<std::size_t, double> Locate(const std::vector<Item>& items, double t)
{
  if (!(t > items.front().time))
  {
    return { 0, 0.0 };
  }
  if (t >= items.back().time)
  {
    return { items.size() - 1, 0.0 };
  }
  const auto next = std::upper_bound(items.begin(), items.end(), t,
    [](double value, const Item& item) { return value < item.time; });
  const std::size_t i = static_cast<std::size_t>(next - items.begin()) - 1;
  return { i, (t - items[i].time) / (items[i + 1].time - items[i].time) };
}

/// A rigid 4x4 from rotation and translation.
Mat4 Rigid(const Mat3& rotation, const Vec3& translation)
{
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = rotation;
  m.topRightCorner<3, 1>() = translation;
  return m;
}

/// The unit quaternion of a (nearly) orthonormal rotation matrix.
Eigen::Quaterniond ToQuaternion(const Mat3& rotation)
{
  return Eigen::Quaterniond(rotation).normalized();
}

/// World-to-camera pose a fraction s of the way from a to b: camera centre linear, rotation slerp.
Mat4 InterpolatePose(const Mat4& a, const Mat4& b, double s)
{
  const PoseFrames fa(a);
  const PoseFrames fb(b);
  const Vec3 centre = (1.0 - s) * fa.centre + s * fb.centre;
  const Mat3 rotation =
    Slerp(ToQuaternion(fa.rotation), ToQuaternion(fb.rotation), s).toRotationMatrix();
  return Rigid(rotation, -rotation * centre);
}

/// "" when m is a finite rigid transform, otherwise what is wrong with it.
std::string RigidityProblem(const Mat4& m)
{
  if (!m.allFinite())
  {
    return "the matrix is not finite";
  }
  if (m(3, 0) != 0.0 || m(3, 1) != 0.0 || m(3, 2) != 0.0 || m(3, 3) != 1.0)
  {
    return "the last row of the matrix is not 0 0 0 1";
  }
  const Mat3 r = m.topLeftCorner<3, 3>();
  const double deviation = (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kRigidTolerance)
  {
    return "the matrix is not rigid (max |R^T R - I| = " + Number(deviation) + " > 1e-6)";
  }
  if (r.determinant() < 0.0)
  {
    return "the matrix is not rigid (det R < 0: a reflection)";
  }
  return "";
}

/// Reads one number: the whole token, an optional leading '+', finite and within range.
bool ParseNumber(std::string_view token, double& value, std::string& why)
{
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-')
  {
    digits.remove_prefix(1);
  }
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range)
  {
    why = Quoted(token) + " is out of the range of a double";
    return false;
  }
  if (ec != std::errc() || end != digits.data() + digits.size())
  {
    why = Quoted(token) + " is not a number";
    return false;
  }
  if (!std::isfinite(value))
  {
    why = Quoted(token) + " is not a finite number";
    return false;
  }
  return true;
}

/// The numbers of one line, split at spaces, tabs, commas (and a CR of a CRLF line end).
void Tokenize(std::string_view line, std::vector<std::string_view>& tokens)
{
  tokens.clear();
  constexpr std::string_view kSeparators = " \t,\r";
  std::size_t start = line.find_first_not_of(kSeparators);
  while (start != std::string_view::npos)
  {
    const std::size_t end = std::min(line.find_first_of(kSeparators, start), line.size());
    tokens.push_back(line.substr(start, end - start));
    start = line.find_first_not_of(kSeparators, end);
  }
}

/// TUM `tx ty tz qx qy qz qw` (camera-to-world: camera centre, Hamilton quaternion scalar last)
/// to world-to-camera: R = R_cw^T, t = -R c.
bool TumToWorldToCamera(const double* v, Mat4& worldToCamera, std::string& why)
{
  const Vec3 centre(v[0], v[1], v[2]);
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]); // Eigen's order: w, x, y, z
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > kQuaternionTolerance)
  {
    why = "the quaternion's norm " + Number(norm) + " is not within 1e-3 of 1";
    return false;
  }
  const Mat3 rotation = q.normalized().toRotationMatrix().transpose();
  worldToCamera = Rigid(rotation, -rotation * centre);
  return true;
}

/// 16 numbers, row-major, to a matrix that must be rigid.
bool MatrixToWorldToCamera(const double* v, Mat4& worldToCamera, std::string& why)
{
  const Mat4 m = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(v);
  why = RigidityProblem(m);
  worldToCamera = m;
  return why.empty();
}

std::string ExpectedCount(std::size_t count)
{
  return "expected " + std::to_string(count) + " numbers (" +
    (count == 8 ? kTumFields : kMatrixFields) + ")";
}

/// One data line's tokens into a pose appended to `poses`. `count` is 0 before the first data
/// line, which sets it to 8 (TUM) or 17 (matrix).
bool ParseLine(const std::vector<std::string_view>& tokens, std::size_t& count,
  std::vector<TimedPose>& poses, std::size_t maxPoses, std::string& why)
{
  const std::size_t found = tokens.size();
  if (count == 0 && found != 8 && found != 17)
  {
    why = "expected 8 numbers (" + std::string(kTumFields) + ") or 17 (" + kMatrixFields +
      "), found " + std::to_string(found);
    return false;
  }
  if (count != 0 && found != count)
  {
    why = ExpectedCount(count) + ", found " + std::to_string(found);
    return false;
  }
  count = found;
  std::array<double, 17> v{};
  for (std::size_t i = 0; i < found; ++i)
  {
    if (!ParseNumber(tokens[i], v[i], why))
    {
      return false;
    }
  }
  if (poses.size() >= maxPoses)
  {
    why = "more than " + std::to_string(maxPoses) + " poses";
    return false;
  }
  if (!poses.empty() && !(v[0] > poses.back().time))
  {
    why = "timestamp " + Number(v[0]) + " is not after the previous one (" +
      Number(poses.back().time) + "); times must increase strictly";
    return false;
  }
  TimedPose pose;
  pose.time = v[0];
  const bool ok = count == 8 ? TumToWorldToCamera(v.data() + 1, pose.worldToCamera, why)
                             : MatrixToWorldToCamera(v.data() + 1, pose.worldToCamera, why);
  if (ok)
  {
    poses.push_back(pose);
  }
  return ok;
}

/// The whole file, or false with a sentence when it cannot be read or is too large.
bool ReadTextFile(const std::string& path, std::string& text, std::string& error)
{
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxTrajectoryFileBytes)
  {
    error = path + ": the file is larger than 1 GiB (" + std::to_string(size) + " bytes)";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = path + ": cannot open the file";
    return false;
  }
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
  {
    if (text.size() + static_cast<std::size_t>(in.gcount()) > kMaxTrajectoryFileBytes)
    {
      error = path + ": the file is larger than 1 GiB";
      return false;
    }
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad())
  {
    error = path + ": cannot read the file (a folder?)";
    return false;
  }
  return true;
}

/// One pose as a line of the format: TUM (camera centre, camera-to-world quaternion with
/// qw >= 0) or matrix (world-to-camera, row-major).
void AppendPose(std::string& out, const TimedPose& pose, bool tum)
{
  AppendNumber(out, pose.time);
  if (tum)
  {
    const PoseFrames frames(pose.worldToCamera);
    Eigen::Quaterniond q = ToQuaternion(frames.rotationT);
    if (q.w() < 0.0)
    {
      q.coeffs() = -q.coeffs();
    }
    const double values[7] = { frames.centre.x(), frames.centre.y(), frames.centre.z(), q.x(),
      q.y(), q.z(), q.w() };
    for (double v : values)
    {
      out += ' ';
      AppendNumber(out, v);
    }
  }
  else
  {
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        out += ' ';
        AppendNumber(out, pose.worldToCamera(r, c));
      }
    }
  }
  out += '\n';
}
} // namespace

Mat4 Trajectory::PoseAt(double t) const
{
  if (this->poses.empty())
  {
    return Mat4::Identity();
  }
  const auto [i, s] = Locate(this->poses, t);
  if (s == 0.0)
  {
    return this->poses[i].worldToCamera;
  }
  return InterpolatePose(this->poses[i].worldToCamera, this->poses[i + 1].worldToCamera, s);
}

int Trajectory::IndexAt(double t, double tolerance) const
{
  if (this->poses.empty() || std::isnan(t))
  {
    return -1;
  }
  const auto next = std::lower_bound(this->poses.begin(), this->poses.end(), t,
    [](const TimedPose& pose, double value) { return pose.time < value; });
  // The nearest is `next` (first at or after t) or the one before it.
  std::size_t best = static_cast<std::size_t>(next - this->poses.begin());
  if (best == this->poses.size() ||
    (best > 0 && t - this->poses[best - 1].time <= this->poses[best].time - t))
  {
    --best;
  }
  return std::abs(this->poses[best].time - t) <= tolerance ? static_cast<int>(best) : -1;
}

std::string Trajectory::Validate() const
{
  for (std::size_t i = 0; i < this->poses.size(); ++i)
  {
    const TimedPose& pose = this->poses[i];
    const std::string where = "poses[" + std::to_string(i) + "]: ";
    if (!std::isfinite(pose.time))
    {
      return where + "the time is not finite";
    }
    if (i > 0 && !(pose.time > this->poses[i - 1].time))
    {
      return where + "time " + Number(pose.time) + " is not after the previous one (" +
        Number(this->poses[i - 1].time) + ")";
    }
    const std::string problem = RigidityProblem(pose.worldToCamera);
    if (!problem.empty())
    {
      return where + problem;
    }
  }
  return "";
}

bool ParseTrajectory(const std::string& text, const std::string& name, Trajectory& trajectory,
  std::string& error, std::size_t maxPoses)
{
  if (text.size() > kMaxTrajectoryFileBytes)
  {
    error = name + ": the text is larger than 1 GiB";
    return false;
  }
  std::vector<TimedPose> poses;
  std::vector<std::string_view> tokens;
  std::size_t count = 0; // numbers per data line: 0 until the first, then 8 or 17
  const std::string_view all(text);
  std::size_t lineNumber = 0;
  for (std::size_t start = 0; start < all.size();)
  {
    const std::size_t end = std::min(all.find('\n', start), all.size());
    const std::string_view line = all.substr(start, end - start);
    start = end + 1;
    ++lineNumber;
    Tokenize(line.substr(0, line.find('#')), tokens);
    std::string why;
    if (!tokens.empty() && !ParseLine(tokens, count, poses, maxPoses, why))
    {
      error = name + " line " + std::to_string(lineNumber) + ": " + why;
      return false;
    }
  }
  if (poses.empty())
  {
    error = name + ": no poses (the file is empty or holds only comments and blank lines)";
    return false;
  }
  trajectory.poses = std::move(poses);
  trajectory.format = count == 8 ? "tum" : "matrix";
  return true;
}

bool LoadTrajectory(const std::string& path, Trajectory& trajectory, std::string& error)
{
  std::string text;
  return ReadTextFile(path, text, error) && ParseTrajectory(text, path, trajectory, error);
}

bool SaveTrajectory(const std::string& path, const Trajectory& trajectory,
  const std::string& format, std::string& error)
{
  if (format != "tum" && format != "matrix")
  {
    error = path + ": unknown trajectory format '" + format + "' (expected tum or matrix)";
    return false;
  }
  const std::string problem =
    trajectory.Empty() ? std::string("no poses to write") : trajectory.Validate();
  if (!problem.empty())
  {
    error = path + ": " + problem;
    return false;
  }
  const bool tum = format == "tum";
  std::string text = tum
    ? "# timestamp tx ty tz qx qy qz qw (TUM: camera-to-world, camera centre, scalar last)\n"
    : "# timestamp, then world-to-camera 4x4 row-major\n";
  for (const TimedPose& pose : trajectory.poses)
  {
    AppendPose(text, pose, tum);
    if (text.size() > kMaxTrajectoryFileBytes)
    {
      error = path + ": the file would be larger than 1 GiB, which LoadTrajectory refuses";
      return false;
    }
  }
  return WriteWholeFile(path, text, error);
}

void Keyframes::At(double t, Vec3& position, Eigen::Quaterniond& rotation) const
{
  if (this->frames.empty())
  {
    position = Vec3::Zero();
    rotation = Eigen::Quaterniond::Identity();
    return;
  }
  const auto [i, s] = Locate(this->frames, t);
  if (s == 0.0)
  {
    position = this->frames[i].position;
    rotation = this->frames[i].rotation;
    return;
  }
  const Keyframe& a = this->frames[i];
  const Keyframe& b = this->frames[i + 1];
  position = (1.0 - s) * a.position + s * b.position;
  rotation = Slerp(a.rotation, b.rotation, s);
}

std::string Keyframes::Validate() const
{
  for (std::size_t i = 0; i < this->frames.size(); ++i)
  {
    const Keyframe& frame = this->frames[i];
    const std::string where = "frames[" + std::to_string(i) + "]: ";
    if (!std::isfinite(frame.time))
    {
      return where + "the time is not finite";
    }
    if (i > 0 && !(frame.time > this->frames[i - 1].time))
    {
      return where + "time " + Number(frame.time) + " is not after the previous one (" +
        Number(this->frames[i - 1].time) + ")";
    }
    if (!frame.position.allFinite())
    {
      return where + "the position is not finite";
    }
    if (!frame.rotation.coeffs().allFinite())
    {
      return where + "the rotation is not finite";
    }
    if (std::abs(frame.rotation.norm() - 1.0) > kUnitTolerance)
    {
      return where + "the rotation quaternion's norm " + Number(frame.rotation.norm()) +
        " is not 1 (within 1e-6)";
    }
  }
  return "";
}
} // namespace catar
