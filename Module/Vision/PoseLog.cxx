#include "PoseLog.h"

#include "Csv.h"
#include "Json.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace catar
{
namespace
{
// A number as text with 17 significant digits ("" for the CSV's empty field is the caller's).
std::string Number(double v)
{
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

// Camera centre (world) and camera-to-world quaternion (x, y, z, w) of a world-to-camera pose.
void TumPose(const Mat4& worldToCamera, Vec3& centre, double quaternion[4])
{
  const PoseFrames frames(worldToCamera);
  centre = frames.centre;
  const Eigen::Quaterniond q = Eigen::Quaterniond(frames.rotationT).normalized();
  quaternion[0] = q.x();
  quaternion[1] = q.y();
  quaternion[2] = q.z();
  quaternion[3] = q.w();
}
} // namespace

std::string PoseLogCsv(const std::vector<LoggedPose>& log)
{
  std::ostringstream s;
  s << "frame,time,verdict,tx,ty,tz,qx,qy,qz,qw,sigma_position_m,sigma_angle_deg,markers,"
       "inliers,corners,rms_px,note\n";
  for (const LoggedPose& entry : log)
  {
    const FramePose& f = entry.pose;
    s << entry.frame << ',' << Number(f.time) << ',' << PoseVerdictName(f.verdict);
    if (f.result.ok)
    {
      Vec3 centre;
      double q[4];
      TumPose(f.result.worldToCamera, centre, q);
      s << ',' << Number(centre.x()) << ',' << Number(centre.y()) << ',' << Number(centre.z());
      for (const double v : q)
      {
        s << ',' << Number(v);
      }
      s << ',' << Number(f.result.uncertainty.positionSigma) << ','
        << Number(f.result.uncertainty.angleSigmaDegrees);
    }
    else
    {
      s << ",,,,,,,,,";
    }
    s << ',' << f.markersFound << ',' << f.result.inlierCount << ',' << f.result.inliers.size()
      << ',' << (f.result.ok ? Number(f.result.rmsPixels) : std::string()) << ','
      << CsvField(f.note) << '\n';
  }
  return s.str();
}

std::string PoseLogJson(const std::vector<LoggedPose>& log)
{
  std::ostringstream s;
  s << "{\"frames\": [";
  for (std::size_t k = 0; k < log.size(); ++k)
  {
    const FramePose& f = log[k].pose;
    s << (k ? ",\n  " : "\n  ") << "{\"frame\": " << log[k].frame
      << ", \"time\": " << JsonNumber(f.time) << ", \"verdict\": \"" << PoseVerdictName(f.verdict)
      << "\", \"markers\": " << f.markersFound;
    if (f.result.ok)
    {
      Vec3 centre;
      double q[4];
      TumPose(f.result.worldToCamera, centre, q);
      const PoseUncertainty& u = f.result.uncertainty;
      s << ", \"position\": [" << JsonNumber(centre.x()) << ", " << JsonNumber(centre.y()) << ", "
        << JsonNumber(centre.z()) << "], \"orientation_xyzw\": [" << JsonNumber(q[0]) << ", "
        << JsonNumber(q[1]) << ", " << JsonNumber(q[2]) << ", " << JsonNumber(q[3])
        << "], \"world_to_camera\": [";
      for (int i = 0; i < 16; ++i)
      {
        s << (i ? ", " : "") << JsonNumber(f.result.worldToCamera(i / 4, i % 4));
      }
      s << "], \"sigma_position_m\": " << JsonNumber(u.positionSigma)
        << ", \"sigma_angle_deg\": " << JsonNumber(u.angleSigmaDegrees)
        << ", \"pixel_sigma\": " << JsonNumber(u.pixelSigma) << ", \"covariance\": [";
      for (int i = 0; i < 36; ++i)
      {
        s << (i ? ", " : "") << JsonNumber(u.covariance(i / 6, i % 6));
      }
      s << "], \"inliers\": " << f.result.inlierCount
        << ", \"corners\": " << f.result.inliers.size()
        << ", \"rms_px\": " << JsonNumber(f.result.rmsPixels);
    }
    s << ", \"note\": " << JsonString(f.note) << "}";
  }
  s << "\n]}\n";
  return s.str();
}
} // namespace catar
