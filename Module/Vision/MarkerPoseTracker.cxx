#include "MarkerPoseTracker.h"

#include "MarkerGrey.h"

#include <Eigen/Geometry>

#include <array>
#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

namespace catar
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

double TurnDegrees(const Mat4& a, const Mat4& b)
{
  const Mat3 d = a.topLeftCorner<3, 3>() * b.topLeftCorner<3, 3>().transpose();
  return Eigen::AngleAxisd(d).angle() * 180.0 / kPi;
}
} // namespace

const char* PoseVerdictName(PoseVerdict verdict)
{
  switch (verdict)
  {
    case PoseVerdict::Reliable:
      return "reliable";
    case PoseVerdict::Unreliable:
      return "unreliable";
    case PoseVerdict::Missing:
      break;
  }
  return "missing";
}

MarkerPoseTracker::MarkerPoseTracker(MarkerBoard board)
  : BoardLayout(std::move(board))
{
}

std::string MarkerPoseTracker::Jump(
  const PoseResult& pose, double time, const PoseResult& from, double fromTime) const
{
  const double dt = time - fromTime;
  if (!(dt > 0.0))
  {
    return std::string();
  }
  const double moved =
    (PoseFrames(pose.worldToCamera).centre - PoseFrames(from.worldToCamera).centre).norm();
  const double turned = TurnDegrees(pose.worldToCamera, from.worldToCamera);
  // Three of the two poses' sigmas together are noise, not motion.
  const double positionNoise =
    3.0 * std::hypot(pose.uncertainty.positionSigma, from.uncertainty.positionSigma);
  const double angleNoise =
    3.0 * std::hypot(pose.uncertainty.angleSigmaDegrees, from.uncertainty.angleSigmaDegrees);
  std::ostringstream s;
  s.precision(3);
  if (moved > this->BoardLayout.maxSpeed * dt + positionNoise)
  {
    s << "the camera jumped " << 1000.0 * moved << " mm in " << dt << " s (max_speed "
      << this->BoardLayout.maxSpeed << " m/s)";
  }
  else if (turned > this->BoardLayout.maxTurnRateDegrees * dt + angleNoise)
  {
    s << "the camera turned " << turned << " degrees in " << dt << " s (max_turn_rate "
      << this->BoardLayout.maxTurnRateDegrees << " degrees/s)";
  }
  return s.str();
}

const FramePose& MarkerPoseTracker::Track(
  const CameraModel& camera, int width, int height, const std::uint8_t* rgba, double time)
{
  const auto start = std::chrono::steady_clock::now();
  std::vector<MarkerDetection> found;
  std::vector<std::array<Vec2, 4>> candidates;
  FramePose f;
  f.time = time;
  if (!DetectMarkers(width, height, rgba, this->BoardLayout.dictionary, true, found, f.result.error,
        &candidates))
  {
    this->Judge(std::move(f));
  }
  else
  {
    f.result = PoseFromMarkers(camera, this->BoardLayout, found, this->BoardLayout.pose);
    // Where the markers must be: this frame's pose when it is reliable, else the last reliable
    // one (the previous frame's, as a rule), else this frame's.
    if (f.result.ok || this->HaveReliable)
    {
      CameraModel posed = camera;
      posed.worldToCamera = (f.result.ok && (f.result.reliable || !this->HaveReliable))
        ? f.result.worldToCamera
        : this->Anchor.worldToCamera;
      const cv::Mat grey = detail::GreyOf(width, height, rgba);
      f.markersRecovered =
        detail::RecoverMarkers(grey, posed, this->BoardLayout, candidates, found);
      // The corners on the markers' edges, the sides bent as the pose projects them; the pose
      // again from them.
      if (detail::RefineMarkerCorners(grey, posed, this->BoardLayout, found) > 0 ||
        f.markersRecovered > 0)
      {
        f.result = PoseFromMarkers(camera, this->BoardLayout, found, this->BoardLayout.pose);
      }
    }
    f.markersFound = static_cast<int>(found.size());
    f.detections = std::move(found);
    this->Judge(std::move(f));
  }
  this->LastPose.seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return this->LastPose;
}

const FramePose& MarkerPoseTracker::Track(
  const CameraModel& camera, const std::vector<MarkerDetection>& found, double time)
{
  const auto start = std::chrono::steady_clock::now();
  FramePose f;
  f.time = time;
  f.markersFound = static_cast<int>(found.size());
  f.detections = found;
  f.result = PoseFromMarkers(camera, this->BoardLayout, found, this->BoardLayout.pose);
  this->Judge(std::move(f));
  this->LastPose.seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return this->LastPose;
}

// The verdict of a frame's estimation, and the tracker's state after it.
const FramePose& MarkerPoseTracker::Judge(FramePose f)
{
  const double time = f.time;
  if (!f.result.ok)
  {
    f.verdict = PoseVerdict::Missing;
    f.note = f.result.error;
  }
  else if (!f.result.reliable)
  {
    f.verdict = PoseVerdict::Unreliable;
    f.note = f.result.warning;
  }
  bool jumped = false;
  if (f.result.ok && f.result.reliable)
  {
    f.verdict = PoseVerdict::Reliable;
    const std::string jump =
      this->HaveReliable ? this->Jump(f.result, time, this->Anchor, this->AnchorTime) : "";
    if (!jump.empty())
    {
      // A second jump that agrees with the first: the anchor was the wrong one.
      const bool confirmed =
        this->HaveJumped && this->Jump(f.result, time, this->Jumped, this->JumpedTime).empty();
      if (!confirmed)
      {
        f.verdict = PoseVerdict::Unreliable;
        f.note = jump;
        f.result.reliable = false;
        f.result.warning = jump;
        this->Jumped = f.result;
        this->JumpedTime = time;
        jumped = true;
      }
    }
  }
  if (f.verdict == PoseVerdict::Reliable)
  {
    this->Anchor = f.result;
    this->AnchorTime = time;
    this->HaveReliable = true;
    this->HaveJumped = false;
  }
  else
  {
    ++this->FailureCount;
    this->HaveJumped = jumped; // a jump is confirmed by the very next frame or not at all
  }
  ++this->FrameCount;
  this->LastPose = std::move(f);
  return this->LastPose;
}

std::string MarkerPoseTracker::Report() const
{
  const FramePose& f = this->LastPose;
  std::ostringstream s;
  if (f.verdict == PoseVerdict::Reliable)
  {
    s << f.markersFound << " markers, " << f.result.inlierCount << " of " << f.result.inliers.size()
      << " corners inliers, " << f.result.rmsPixels << " px rms, one sigma "
      << 1000.0 * f.result.uncertainty.positionSigma << " mm, "
      << f.result.uncertainty.angleSigmaDegrees << " degrees";
  }
  else
  {
    s << (f.verdict == PoseVerdict::Unreliable ? "pose unreliable (" : "no pose (") << f.note
      << "): " << (this->HaveReliable ? "the previous one kept" : "no pose yet");
  }
  return s.str();
}
} // namespace catar
