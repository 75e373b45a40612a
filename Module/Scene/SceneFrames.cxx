#include "SceneFrames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace catar
{
bool SceneFrames::Plan(
  const SceneDescription& scene, long long videoFrames, double videoFps, std::string& error)
{
  *this = SceneFrames();
  this->Scene = &scene;
  const Trajectory& trajectory = scene.trajectory;
  const long long poses = static_cast<long long>(trajectory.poses.size());
  this->Video = scene.background.type == "video";
  if (this->Video)
  {
    if (videoFrames < 1)
    {
      error = "the background video has no frames";
      return false;
    }
    this->VideoFps = scene.background.fps > 0.0 ? scene.background.fps : videoFps;
    this->ByTime = scene.background.match == "time" || trajectory.Empty();
    if (this->ByTime && !(this->VideoFps > 0.0))
    {
      error = "background: the frames have no rate of their own (an image sequence): give 'fps'";
      return false;
    }
    this->count = this->ByTime ? videoFrames : std::min(videoFrames, poses);
    if (!this->ByTime && videoFrames != poses)
    {
      this->note = "the background has " + std::to_string(videoFrames) +
        " frames and the trajectory " + std::to_string(poses) + " poses: rendering " +
        std::to_string(this->count);
    }
    this->fps = this->VideoFps > 0.0 ? this->VideoFps : 30.0;
    return true;
  }
  if (!trajectory.Empty())
  {
    this->count = poses;
    const double span = trajectory.poses.back().time - trajectory.poses.front().time;
    this->fps = poses > 1 && span > 0.0 ? static_cast<double>(poses - 1) / span : 30.0;
    this->fps = std::min(1000.0, std::max(0.001, this->fps));
    return true;
  }
  this->count = scene.sequence.frames;
  this->fps = scene.sequence.fps;
  if (!scene.sequence.given)
  {
    // Keyframes and no `sequence`: the frames the keyframes span, at the sequence's rate (one
    // frame, before, and nothing said).
    double last = 0.0;
    for (const SceneObject& o : scene.objects)
    {
      last = o.keyframes.frames.empty() ? last : std::max(last, o.keyframes.frames.back().time);
    }
    for (const SceneLight& l : scene.lighting.lights)
    {
      last = l.keyframes.empty() ? last : std::max(last, l.keyframes.back().time);
    }
    if (last > 0.0)
    {
      this->count = static_cast<long long>(std::min(1e7, std::floor(last * this->fps + 1e-9) + 1));
      char text[200];
      std::snprintf(text, sizeof text,
        "the keyframes run to %g s and the scene has no 'sequence': rendering %lld frames at %g "
        "frames a second (give 'sequence: { frames: N }' for another number)",
        last, this->count, this->fps);
      this->note = text;
    }
  }
  return true;
}

double SceneFrames::Time(long long k) const
{
  if (this->ByTime)
  {
    return this->Scene->background.startTime + static_cast<double>(k) / this->VideoFps;
  }
  const Trajectory& trajectory = this->Scene->trajectory;
  if (!trajectory.Empty())
  {
    const long long last = static_cast<long long>(trajectory.poses.size()) - 1;
    return trajectory.poses[static_cast<std::size_t>(std::max(0LL, std::min(k, last)))].time;
  }
  return static_cast<double>(k) / this->fps;
}

Mat4 SceneFrames::Pose(long long k) const
{
  const Trajectory& trajectory = this->Scene->trajectory;
  if (trajectory.Empty())
  {
    return this->Scene->camera.worldToCamera;
  }
  if (this->ByTime)
  {
    return trajectory.PoseAt(this->Time(k));
  }
  const long long last = static_cast<long long>(trajectory.poses.size()) - 1;
  return trajectory.poses[static_cast<std::size_t>(std::max(0LL, std::min(k, last)))].worldToCamera;
}

long long SceneFrames::VideoFrame(long long k) const
{
  return this->Video ? k : -1;
}
} // namespace catar
