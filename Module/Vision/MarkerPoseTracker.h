// CatadioptricAR Core: the camera's pose of each frame of a sequence from the markers seen in it,
// with a verdict per frame.
//
// Each frame: the board's markers are detected (DetectMarkers), the pose is estimated from them
// (PoseFromMarkers, with the board's guards); the board's markers that were found as shapes but
// not decoded are read again where that pose -- or, without one, the last reliable pose -- puts
// them (RecoverMarkers), and the pose estimated again with them; then it is checked against the
// last reliable pose:
// a pose that moved the camera faster than the board's max_speed or turned it faster than
// max_turn_rate (beyond three of the two poses' sigmas) is flagged as a jump. Two jumps in a row
// that agree with each other are taken as the camera's new place (the earlier pose was the wrong
// one), so that one bad frame cannot hold every later frame back.
#ifndef catarMarkerPoseTracker_h
#define catarMarkerPoseTracker_h

#include "Markers.h"

#include <cstdint>
#include <string>
#include <vector>

namespace catar
{
enum class PoseVerdict
{
  Reliable,   ///< found, and every guard holds
  Unreliable, ///< found, but flagged (FramePose::note says why)
  Missing     ///< no pose (no marker of the board, or the estimation refused)
};

/// "reliable", "unreliable", "missing".
const char* PoseVerdictName(PoseVerdict verdict);

struct FramePose
{
  double time = 0.0;
  PoseVerdict verdict = PoseVerdict::Missing;
  PoseResult result;        ///< the estimation (result.ok for Reliable and Unreliable)
  int markersFound = 0;     ///< markers of the board's dictionary found in the frame
  int markersRecovered = 0; ///< of them, read again where the pose puts them (RecoverMarkers)
  std::vector<MarkerDetection> detections; ///< the markers found, with their corners
  std::string note;     ///< why not reliable: the estimation's error or the guard's warning
  double seconds = 0.0; ///< detection and estimation
};

class MarkerPoseTracker
{
public:
  explicit MarkerPoseTracker(MarkerBoard board = {});

  /// The pose of one RGBA8 frame (top row first) at `time` seconds. Frames are expected in
  /// time order; a time not after the last reliable pose's skips the motion check.
  const FramePose& Track(
    const CameraModel& camera, int width, int height, const std::uint8_t* rgba, double time);
  /// The same from markers already found in the frame.
  const FramePose& Track(
    const CameraModel& camera, const std::vector<MarkerDetection>& found, double time);

  const FramePose& Last() const { return this->LastPose; }
  const MarkerBoard& Board() const { return this->BoardLayout; }
  bool AnyReliable() const { return this->HaveReliable; }
  /// Frames tracked, and of them those without a reliable pose.
  int Frames() const { return this->FrameCount; }
  int Failures() const { return this->FailureCount; }
  /// One line on the last frame: markers, inliers, error and one sigma; or why it has no pose.
  std::string Report() const;

private:
  const FramePose& Judge(FramePose f);
  // "" when `pose` is consistent with the last reliable pose, else the jump's sentence.
  std::string Jump(
    const PoseResult& pose, double time, const PoseResult& from, double fromTime) const;

  MarkerBoard BoardLayout;
  FramePose LastPose;
  PoseResult Anchor; // the last reliable pose
  double AnchorTime = 0.0;
  bool HaveReliable = false;
  // The last frame's pose when it was flagged as a jump (a second that agrees re-anchors).
  PoseResult Jumped;
  double JumpedTime = 0.0;
  bool HaveJumped = false;
  int FrameCount = 0;
  int FailureCount = 0;
};
} // namespace catar

#endif
