// CatadioptricAR Core: the frames of a scene's sequence — how many, and for frame k its time,
// the camera's pose and the background's frame (SceneDescription.h: `trajectory`, a `video`
// background, `sequence`, keyframes).
#ifndef catarSceneFrames_h
#define catarSceneFrames_h

#include "SceneDescription.h"

#include <string>

namespace catar
{
/// The plan of a sequence (SceneFrames::Plan). Frame k:
///  - with a trajectory, and no video or a video matched by index: the time of pose k, pose k,
///    video frame k (the shorter of the two sets the count);
///  - with a video matched by time (or a video and no trajectory): time start_time + k / fps,
///    the trajectory's pose at that time (the calibration's without a trajectory), video frame k;
///  - otherwise (`sequence`): time k / fps, the calibration's pose.
/// Objects and lights take their keyframes at the frame's time.
struct SceneFrames
{
  long long count = 1;
  double fps = 30.0; ///< frames a second of the output (the video's, the trajectory's mean, or
                     ///< `sequence.fps`)
  std::string note;  ///< a sentence when the count was cut to the shorter of video and trajectory

  /// Plans the frames of scene; videoFrames and videoFps describe its background video (ignored
  /// without one; videoFps 0 when the video gives none). False with a sentence in error (a video
  /// matched by time without a frame rate, a video with no frames).
  bool Plan(
    const SceneDescription& scene, long long videoFrames, double videoFps, std::string& error);
  double Time(long long k) const;
  /// The world-to-camera pose of frame k.
  Mat4 Pose(long long k) const;
  /// The background video's frame for frame k (-1 without a video).
  long long VideoFrame(long long k) const;

private:
  const SceneDescription* Scene = nullptr;
  bool Video = false;
  bool ByTime = false; // times from the video's rate, poses interpolated
  double VideoFps = 0.0;
};
} // namespace catar

#endif
