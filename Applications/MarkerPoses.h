// catadioptric-render's record of the poses found from markers: each rendered frame's verdict,
// written by --poses-out (TUM: the reliable poses; CSV or JSON: every frame with its verdict and
// uncertainty, PoseLog.h), and the run's status when frames had no reliable pose: 3 unless
// --allow-missing-poses, with a line that says how many frames kept which pose.
#ifndef catarMarkerPoses_h
#define catarMarkerPoses_h

#include "vtkCatadioptricSceneRenderer.h"

#include "FileOutput.h"
#include "MarkerPoseTracker.h"
#include "PoseLog.h"
#include "Trajectory.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

namespace catar_render
{
/// The exit status of a run whose frames did not all have a reliable pose.
constexpr int kMissingPosesStatus = 3;

class MarkerPoses
{
public:
  std::string path;          ///< --poses-out; "" when not asked for
  bool allowMissing = false; ///< --allow-missing-poses

  /// "" when `path` has a known extension (.tum, .txt, .csv, .json), else the sentence.
  std::string CheckPath() const
  {
    const std::string e = this->Extension();
    return e == ".tum" || e == ".txt" || e == ".csv" || e == ".json"
      ? std::string()
      : "--poses-out writes FILE.tum or FILE.txt (a TUM trajectory of the reliable poses), "
        "FILE.csv or FILE.json (every frame with its verdict and uncertainty)";
  }

  /// Records the frame just rendered (nothing when the scene does not use markers).
  void Add(vtkCatadioptricSceneRenderer* renderer, long long frame)
  {
    if (!renderer->GetUsesMarkers())
    {
      return;
    }
    catar::LoggedPose entry;
    entry.frame = frame;
    entry.pose = renderer->GetFramePose();
    entry.pose.time = renderer->GetFrameTime(static_cast<int>(frame));
    this->log.push_back(entry);
  }

  /// Writes --poses-out (whole or not at all); false with the reason printed.
  bool Write(bool quiet) const
  {
    if (this->path.empty())
    {
      return true;
    }
    std::string error;
    bool written = false;
    std::string what;
    const std::string e = this->Extension();
    if (e == ".csv" || e == ".json")
    {
      written = catar::WriteWholeFile(this->path,
        e == ".csv" ? catar::PoseLogCsv(this->log) : catar::PoseLogJson(this->log), error);
      what = "the poses of " + std::to_string(this->log.size()) +
        " frames with their verdicts and uncertainty";
    }
    else
    {
      catar::Trajectory trajectory;
      for (const catar::LoggedPose& entry : this->log)
      {
        if (entry.pose.verdict == catar::PoseVerdict::Reliable)
        {
          trajectory.poses.push_back({ entry.pose.time, entry.pose.result.worldToCamera });
        }
      }
      if (trajectory.Empty())
      {
        std::fprintf(stderr,
          "catadioptric-render: --poses-out %s: no frame had a reliable pose from its markers; "
          "nothing written (a .csv or .json file lists every frame's verdict)\n",
          this->path.c_str());
        return false;
      }
      written = catar::SaveTrajectory(this->path, trajectory, "tum", error);
      what = "the reliable poses of " + std::to_string(trajectory.poses.size()) + " frames (" +
        std::to_string(this->log.size() - trajectory.poses.size()) + " without one left out)";
    }
    if (!written)
    {
      std::fprintf(stderr, "catadioptric-render: --poses-out: %s\n", error.c_str());
      return false;
    }
    if (!quiet)
    {
      std::printf("wrote %s to %s\n", what.c_str(), this->path.c_str());
    }
    return true;
  }

  /// After the run: 0 when every frame had a reliable pose (or none uses markers); else prints
  /// what the frames without one drew and returns kMissingPosesStatus, or 0 with
  /// --allow-missing-poses (the line is then a note).
  int Status() const
  {
    long long unreliable = 0;
    long long missing = 0;
    long long beforeFirst = 0;
    const catar::LoggedPose* first = nullptr;
    bool seenReliable = false;
    for (const catar::LoggedPose& entry : this->log)
    {
      const catar::PoseVerdict v = entry.pose.verdict;
      if (v == catar::PoseVerdict::Reliable)
      {
        seenReliable = true;
        continue;
      }
      unreliable += v == catar::PoseVerdict::Unreliable ? 1 : 0;
      missing += v == catar::PoseVerdict::Missing ? 1 : 0;
      beforeFirst += seenReliable ? 0 : 1;
      first = first ? first : &entry;
    }
    if (!first)
    {
      return 0;
    }
    const long long without = unreliable + missing;
    std::string line = std::to_string(without) + " of " + std::to_string(this->log.size()) +
      " frames had no reliable pose from their markers (" + std::to_string(unreliable) +
      " flagged unreliable, " + std::to_string(missing) + " without a pose; the first, frame " +
      std::to_string(first->frame) + ": " + first->pose.note + "): ";
    if (beforeFirst == static_cast<long long>(this->log.size()))
    {
      line += "every frame was drawn at the scene's own camera pose";
    }
    else
    {
      line += std::to_string(without - beforeFirst) + " kept the previous frame's pose";
      if (beforeFirst > 0)
      {
        line += ", " + std::to_string(beforeFirst) +
          " before the first reliable pose were drawn at the scene's own camera pose";
      }
    }
    if (this->allowMissing)
    {
      std::fprintf(stderr, "catadioptric-render: note: %s\n", line.c_str());
      return 0;
    }
    std::fprintf(stderr,
      "catadioptric-render: %s; the outputs are written, the status is %d "
      "(--allow-missing-poses accepts them)\n",
      line.c_str(), kMissingPosesStatus);
    return kMissingPosesStatus;
  }

private:
  std::string Extension() const
  {
    const std::size_t dot = this->path.rfind('.');
    std::string e = dot == std::string::npos ? std::string() : this->path.substr(dot);
    std::transform(e.begin(), e.end(), e.begin(),
      [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
  }

  std::vector<catar::LoggedPose> log;
};
} // namespace catar_render

#endif
