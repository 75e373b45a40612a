#include "CalibrationIO.h"

#include "FileStorageUtil.h"

#include <opencv2/core.hpp>

#include <cmath>
#include <sstream>

namespace catar
{
namespace fs
{
std::vector<double> Numbers(const cv::FileNode& node, const std::string& key)
{
  std::vector<double> out;
  if (node.empty() || node.isNone())
  {
    throw ParseError("missing key '" + key + "'");
  }
  if (node.isReal() || node.isInt())
  {
    out.push_back(static_cast<double>(node));
  }
  else if (node.isSeq())
  {
    for (cv::FileNodeIterator it = node.begin(); it != node.end(); ++it)
    {
      const cv::FileNode item = *it;
      if (!(item.isReal() || item.isInt()))
      {
        throw ParseError("'" + key + "' must contain only numbers");
      }
      out.push_back(static_cast<double>(item));
    }
  }
  else if (node.isMap() && !node["data"].empty())
  {
    cv::Mat m;
    node >> m;
    if (m.empty())
    {
      throw ParseError("'" + key + "' is not a readable matrix");
    }
    cv::Mat d;
    m.convertTo(d, CV_64F);
    d = d.reshape(1, 1);
    out.assign(d.ptr<double>(), d.ptr<double>() + d.total());
  }
  else
  {
    throw ParseError("'" + key + "' must be a number, a sequence or a matrix");
  }
  for (double v : out)
  {
    if (!std::isfinite(v))
    {
      throw ParseError("'" + key + "' contains NaN or Inf");
    }
  }
  return out;
}

std::vector<double> Numbers(const cv::FileNode& node, const std::string& key, size_t n)
{
  std::vector<double> v = Numbers(node, key);
  if (v.size() != n)
  {
    std::ostringstream msg;
    msg << "'" << key << "' must have " << n << " numbers, found " << v.size();
    throw ParseError(msg.str());
  }
  return v;
}

double Number(const cv::FileNode& parent, const std::string& key, double fallback)
{
  const cv::FileNode n = parent[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  return Numbers(n, key, 1)[0];
}

double Number(const cv::FileNode& parent, const std::string& key)
{
  return Numbers(parent[key], key, 1)[0];
}

std::string String(const cv::FileNode& parent, const std::string& key, const std::string& fallback)
{
  const cv::FileNode n = parent[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  if (!n.isString())
  {
    throw ParseError("'" + key + "' must be a string");
  }
  return static_cast<std::string>(n);
}

void ReadCalibration(const cv::FileNode& node, CameraModel& m)
{
  if (!node.isMap())
  {
    throw ParseError("the calibration must be a map of keys");
  }
  CameraModel model;
  const double w = Number(node, "image_width");
  const double h = Number(node, "image_height");
  if (w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > 1e5 || h > 1e5)
  {
    throw ParseError("'image_width' and 'image_height' must be positive integers");
  }
  model.intrinsics.width = static_cast<int>(w);
  model.intrinsics.height = static_cast<int>(h);
  const std::vector<double> K = Numbers(node["camera_matrix"], "camera_matrix", 9);
  if (K[3] != 0.0 || K[6] != 0.0 || K[7] != 0.0 || K[8] != 1.0)
  {
    throw ParseError("'camera_matrix' must be [fx s cx; 0 fy cy; 0 0 1]");
  }
  model.intrinsics.fx = K[0];
  model.intrinsics.skew = K[1];
  model.intrinsics.cx = K[2];
  model.intrinsics.fy = K[4];
  model.intrinsics.cy = K[5];
  const cv::FileNode dn = node["distortion_coefficients"];
  if (!dn.empty() && !dn.isNone())
  {
    std::vector<double> d = Numbers(dn, "distortion_coefficients");
    if (d.size() != 4 && d.size() != 5)
    {
      throw ParseError("'distortion_coefficients' must have 4 or 5 numbers (k1 k2 p1 p2 [k3]); "
                       "rational and thin-prism models are not supported");
    }
    d.resize(5, 0.0);
    model.distortion = Distortion{ d[0], d[1], d[2], d[3], d[4] };
  }
  const cv::FileNode mirror = node["mirror"];
  if (!mirror.isMap())
  {
    throw ParseError("missing map 'mirror' {type, center, radius}");
  }
  const std::string type = String(mirror, "type", "sphere");
  if (type != "sphere")
  {
    throw ParseError("mirror type '" + type + "' is not supported (only 'sphere')");
  }
  const std::vector<double> c = Numbers(mirror["center"], "mirror.center", 3);
  model.mirror.center = Vec3(c[0], c[1], c[2]);
  model.mirror.radius = Number(mirror, "radius");
  const cv::FileNode pose = node["world_to_camera"];
  if (!pose.empty() && !pose.isNone())
  {
    const std::vector<double> p = Numbers(pose, "world_to_camera", 16);
    for (int r = 0; r < 4; ++r)
    {
      for (int col = 0; col < 4; ++col)
      {
        model.worldToCamera(r, col) = p[4 * r + col];
      }
    }
  }
  const std::string problem = model.Validate();
  if (!problem.empty())
  {
    throw ParseError(problem);
  }
  m = model;
}
} // namespace fs

namespace
{
bool ReadStorage(
  cv::FileStorage& storage, const std::string& what, CameraModel& model, std::string& error)
{
  try
  {
    fs::ReadCalibration(storage.root(), model);
    return true;
  }
  catch (const std::exception& e)
  {
    error = what + ": " + e.what();
    return false;
  }
}

void WriteStorage(cv::FileStorage& out, const CameraModel& m)
{
  out << "image_width" << m.intrinsics.width;
  out << "image_height" << m.intrinsics.height;
  cv::Mat K(3, 3, CV_64F);
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(K.ptr<double>()) = m.K();
  out << "camera_matrix" << K;
  const Distortion& d = m.distortion;
  cv::Mat D = (cv::Mat_<double>(1, 5) << d.k1, d.k2, d.p1, d.p2, d.k3);
  out << "distortion_coefficients" << D;
  out << "mirror"
      << "{";
  out << "type"
      << "sphere";
  out << "center"
      << "[:" << m.mirror.center.x() << m.mirror.center.y() << m.mirror.center.z() << "]";
  out << "radius" << m.mirror.radius;
  out << "}";
  cv::Mat P(4, 4, CV_64F);
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(P.ptr<double>()) = m.worldToCamera;
  out << "world_to_camera" << P;
}
} // namespace

bool LoadCalibration(const std::string& path, CameraModel& model, std::string& error)
{
  cv::FileStorage storage;
  try
  {
    if (!storage.open(path, cv::FileStorage::READ))
    {
      error = path + ": cannot open the calibration file";
      return false;
    }
  }
  catch (const cv::Exception& e)
  {
    error = path + ": not a valid YAML/JSON file (" + e.msg + ")";
    return false;
  }
  return ReadStorage(storage, path, model, error);
}

bool ParseCalibration(const std::string& text, CameraModel& model, std::string& error)
{
  cv::FileStorage storage;
  try
  {
    if (!storage.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY))
    {
      error = "calibration text: cannot be parsed";
      return false;
    }
  }
  catch (const cv::Exception& e)
  {
    error = "calibration text: not valid YAML/JSON (" + e.msg + ")";
    return false;
  }
  return ReadStorage(storage, "calibration text", model, error);
}

bool SaveCalibration(const std::string& path, const CameraModel& model, std::string& error)
{
  const std::string problem = model.Validate();
  if (!problem.empty())
  {
    error = "refusing to save an invalid camera: " + problem;
    return false;
  }
  try
  {
    cv::FileStorage out(path, cv::FileStorage::WRITE);
    if (!out.isOpened())
    {
      error = path + ": cannot open for writing";
      return false;
    }
    WriteStorage(out, model);
    out.release();
  }
  catch (const cv::Exception& e)
  {
    error = path + ": " + e.msg;
    return false;
  }
  return true;
}

std::string CalibrationToString(const CameraModel& model, bool json)
{
  cv::FileStorage out(json ? ".json" : ".yaml",
    cv::FileStorage::WRITE | cv::FileStorage::MEMORY |
      (json ? cv::FileStorage::FORMAT_JSON : cv::FileStorage::FORMAT_YAML));
  WriteStorage(out, model);
  return out.releaseAndGetString();
}
} // namespace catar
