// CatadioptricAR Core: the per-frame poses of a sequence from its markers, written with their
// verdict and uncertainty (MarkerPoseTracker.h), as CSV or JSON.
//
// One row (CSV) or object (JSON) a frame: the frame's number and time, the verdict (reliable,
// unreliable, missing), the camera's pose as TUM gives it (camera centre in the world, and the
// camera-to-world rotation as a unit quaternion, scalar last) when a pose was estimated (also for
// an unreliable one), its one-sigma uncertainty (camera centre in metres, rotation in degrees),
// the markers found, the corners that fit out of those used, their RMS error in pixels, and the
// note that says why a frame has no reliable pose. JSON adds the world-to-camera matrix and the
// 6 x 6 covariance (camera rotation about world axes in radians, then the centre in metres).
#ifndef catarPoseLog_h
#define catarPoseLog_h

#include "MarkerPoseTracker.h"

#include <string>
#include <vector>

namespace catar
{
struct LoggedPose
{
  long long frame = 0;
  FramePose pose;
};

/// The log as CSV (with a header line) or JSON text.
std::string PoseLogCsv(const std::vector<LoggedPose>& log);
std::string PoseLogJson(const std::vector<LoggedPose>& log);
} // namespace catar

#endif
