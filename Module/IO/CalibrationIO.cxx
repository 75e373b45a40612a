#include "CalibrationIO.h"

#include "ConfigReader.h"
#include "DemoCameraText.h"
#include "FileOutput.h"
#include "Mirror.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace catar
{
namespace fs
{
namespace
{
// The mirror map: its type (the default type when absent) and that type's keys, each a number or
// a list of numbers (MirrorTypes() says which).
MirrorDescription ReadMirror(const Node& mirror)
{
  const MirrorType& fallback = MirrorTypes().front();
  if (!mirror.isMap())
  {
    std::string keys = "type";
    for (const MirrorParameter& p : fallback.parameters)
    {
      keys += ", " + p.key;
    }
    throw ParseError("missing map 'mirror' {" + keys + "}");
  }
  const std::string typeName = String(mirror, "type", fallback.name);
  const MirrorType* type = FindMirrorType(typeName);
  // The keys of the type's variants (a misspelt key is an error, not a silently used default).
  std::vector<std::string> known = { "type" };
  for (const MirrorType& t : MirrorTypes())
  {
    for (const MirrorParameter& p : t.parameters)
    {
      if (t.name == typeName && std::find(known.begin(), known.end(), p.key) == known.end())
      {
        known.push_back(p.key);
      }
    }
  }
  if (type)
  {
    try
    {
      CheckKeys(mirror, known);
    }
    catch (const ParseError& e)
    {
      throw ParseError("mirror type '" + typeName + "': " + e.what());
    }
  }
  // Of a name's variants, the first whose keys are all there (else the first, whose missing key
  // the error names).
  for (const MirrorType& t : MirrorTypes())
  {
    if (t.name != typeName)
    {
      continue;
    }
    bool all = true;
    for (const MirrorParameter& p : t.parameters)
    {
      all = all && !mirror[p.key].empty();
    }
    if (all)
    {
      type = &t;
      break;
    }
  }
  if (!type)
  {
    throw ParseError(
      "mirror type '" + typeName + "' is not supported (known: " + MirrorTypeNames() + ")");
  }
  MirrorDescription d(type->name, {});
  try
  {
    for (const MirrorParameter& p : type->parameters)
    {
      if (p.count == 1)
      {
        d.parameters.push_back(Number(mirror, p.key));
      }
      else
      {
        const std::vector<double> v = Numbers(mirror[p.key], "mirror." + p.key, p.count);
        d.parameters.insert(d.parameters.end(), v.begin(), v.end());
      }
    }
  }
  catch (const ParseError& e)
  {
    throw ParseError("mirror type '" + type->name + "': " + e.what());
  }
  return d;
}

// A matrix as a list of numbers, or in ROS camera_info's form { rows, cols, data }; n numbers
// (0: any count).
std::vector<double> MatrixNumbers(const Node& node, const std::string& key, std::size_t n)
{
  if (node.isMap())
  {
    const double rows = Number(node, "rows"), cols = Number(node, "cols");
    std::vector<double> data = Numbers(node["data"], key + ".data");
    if (!(rows >= 1 && cols >= 1 && rows * cols == static_cast<double>(data.size())))
    {
      throw ParseError("'" + key + "': rows x cols must be the number of values in data");
    }
    if (n > 0 && data.size() != n)
    {
      throw ParseError("'" + key + "' must have " + std::to_string(n) + " numbers");
    }
    return data;
  }
  return n > 0 ? Numbers(node, key, n) : Numbers(node, key);
}
} // namespace

void ReadCalibration(const Node& node, CameraModel& m, bool mirrorRequired)
{
  if (!node.isMap())
  {
    throw ParseError("the calibration must be a map of keys");
  }
  CheckKeys(node,
    { "image_width", "image_height", "camera_matrix", "lens", "distortion_model",
      "distortion_coefficients", "calibration", "mirror", "world_to_camera",
      // Read past: the rest of a ROS camera_info file ...
      "camera_name", "rectification_matrix", "projection_matrix",
      // ... and of the files OpenCV's calibration samples write.
      "calibration_time", "nframes", "nr_of_frames", "board_width", "board_height", "square_size",
      "aspectRatio", "fix_aspect_ratio", "flags", "fisheye_model", "avg_reprojection_error",
      "per_view_reprojection_errors", "extrinsic_parameters", "image_points", "grid_points" });
  CameraModel model;
  const double w = Number(node, "image_width");
  const double h = Number(node, "image_height");
  if (!(w == std::floor(w) && h == std::floor(h) && w >= 1 && h >= 1))
  {
    throw ParseError("'image_width' and 'image_height' must be positive integers");
  }
  if (w > kMaxImageSide || h > kMaxImageSide || w * h > static_cast<double>(kMaxImagePixels))
  {
    throw ParseError("'image_width' x 'image_height' is over the limit of " +
      std::to_string(kMaxImageSide) + " pixels a side and " + std::to_string(kMaxImagePixels) +
      " pixels");
  }
  model.intrinsics.width = static_cast<int>(w);
  model.intrinsics.height = static_cast<int>(h);
  const std::vector<double> K = MatrixNumbers(node["camera_matrix"], "camera_matrix", 9);
  if (K[3] != 0.0 || K[6] != 0.0 || K[7] != 0.0 || K[8] != 1.0)
  {
    throw ParseError("'camera_matrix' must be [fx s cx; 0 fy cy; 0 0 1]");
  }
  model.intrinsics.fx = K[0];
  model.intrinsics.skew = K[1];
  model.intrinsics.cx = K[2];
  model.intrinsics.fy = K[4];
  model.intrinsics.cy = K[5];
  // The lens: `lens: pinhole | fisheye`, or ROS camera_info's distortion_model (plumb_bob and
  // rational_polynomial: OpenCV's pinhole; equidistant: the fisheye), or the flag fisheye_model of
  // OpenCV's calibration sample.
  LensType lens = Flag(node, "fisheye_model", false) ? LensType::Fisheye : LensType::Pinhole;
  const std::string lensName = String(node, "lens", "");
  if (!lensName.empty())
  {
    const LensType flagged = lens;
    if (!LensFromName(lensName, lens))
    {
      throw ParseError("'lens' " + lensName + " is not a lens model (pinhole or fisheye)");
    }
    if (flagged == LensType::Fisheye && lens != flagged)
    {
      throw ParseError("'fisheye_model' contradicts 'lens' " + lensName);
    }
  }
  const std::string distortionModel = String(node, "distortion_model", "");
  if (!distortionModel.empty())
  {
    const LensType named = distortionModel == "equidistant" ? LensType::Fisheye : LensType::Pinhole;
    if (distortionModel != "plumb_bob" && distortionModel != "rational_polynomial" &&
      distortionModel != "equidistant")
    {
      throw ParseError("'distortion_model' " + distortionModel +
        " is not supported (plumb_bob, rational_polynomial: OpenCV's pinhole; equidistant: the "
        "fisheye)");
    }
    if ((!lensName.empty() || lens == LensType::Fisheye) && named != lens)
    {
      throw ParseError(
        "'distortion_model' " + distortionModel + " contradicts the lens " + LensName(lens));
    }
    lens = named;
  }
  model.lens = lens;
  model.distortion = Distortion();
  const Node dn = node["distortion_coefficients"];
  if (!dn.empty() && !dn.isNone())
  {
    const std::vector<double> d = MatrixNumbers(dn, "distortion_coefficients", 0);
    if (!model.distortion.SetCoefficients(lens, d))
    {
      throw ParseError(lens == LensType::Fisheye
          ? "'distortion_coefficients' of a fisheye lens must have 4 numbers (k1 k2 k3 k4)"
          : "'distortion_coefficients' must have 4, 5, 8, 12 or 14 numbers (OpenCV's k1 k2 p1 p2 "
            "[k3 [k4 k5 k6 [s1 s2 s3 s4 [tauX tauY]]]])");
    }
    // OpenCV's calibrations of real lenses give coefficients of a few units (wide-angle lenses a
    // few hundred at most); 1e10 is a typing error that would send every ray off the image.
    for (const double k : d)
    {
      if (!(std::abs(k) <= 1e4))
      {
        std::ostringstream s;
        s << "'distortion_coefficients' " << k
          << " is not a lens's (each must be within +-1e4; OpenCV's model)";
        throw ParseError(s.str());
      }
    }
  }
  if (mirrorRequired || !node["mirror"].empty())
  {
    model.mirror = ReadMirror(node["mirror"]);
  }
  const Node pose = node["world_to_camera"];
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
bool ReadRoot(const fs::Node& root, const std::string& what, CameraModel& model, std::string& error,
  bool mirrorRequired = true)
{
  try
  {
    fs::ReadCalibration(root, model, mirrorRequired);
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
  if (m.lens != LensType::Pinhole)
  {
    out << "lens" << LensName(m.lens);
  }
  const std::vector<double> d = m.distortion.Coefficients(m.lens);
  cv::Mat D(1, static_cast<int>(d.size()), CV_64F);
  std::copy(d.begin(), d.end(), D.ptr<double>());
  out << "distortion_coefficients" << D;
  out << "mirror"
      << "{";
  out << "type" << m.mirror.type;
  if (const MirrorType* type = FindMirrorType(m.mirror.type, m.mirror.parameters.size()))
  {
    std::size_t i = 0;
    for (const MirrorParameter& p : type->parameters)
    {
      out << p.key;
      if (p.count == 1)
      {
        out << m.mirror.parameters.at(i++);
        continue;
      }
      out << "[:";
      for (int k = 0; k < p.count; ++k)
      {
        out << m.mirror.parameters.at(i++);
      }
      out << "]";
    }
  }
  out << "}";
  cv::Mat P(4, 4, CV_64F);
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(P.ptr<double>()) = m.worldToCamera;
  out << "world_to_camera" << P;
}
} // namespace

bool LoadCalibration(const std::string& path, CameraModel& model, std::string& error)
{
  fs::Node root;
  return fs::Parse(path, false, path, root, error) && ReadRoot(root, path, model, error);
}

bool LoadLensCalibration(const std::string& path, CameraModel& model, std::string& error)
{
  fs::Node root;
  return fs::Parse(path, false, path, root, error) && ReadRoot(root, path, model, error, false);
}

bool ParseCalibration(const std::string& text, CameraModel& model, std::string& error)
{
  fs::Node root;
  return fs::Parse(text, true, "calibration text", root, error) &&
    ReadRoot(root, "calibration text", model, error);
}

bool SaveCalibration(const std::string& path, const CameraModel& model, std::string& error,
  const CalibrationRecord* record)
{
  const std::string problem = model.Validate();
  if (!problem.empty())
  {
    error = "refusing to save an invalid camera: " + problem;
    return false;
  }
  // Made in memory, then written with every error checked (a full disk is an error).
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  const bool hasExt = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  std::string ext = hasExt ? path.substr(dot) : std::string(".yaml");
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".yaml" && ext != ".yml" && ext != ".json")
  {
    error = path + ": cannot write a calibration in this format (.yaml, .yml or .json)";
    return false;
  }
  std::string text;
  try
  {
    text = CalibrationToString(model, ext == ".json", record);
  }
  catch (const cv::Exception& e)
  {
    error = path + ": " + e.msg;
    return false;
  }
  return WriteWholeFile(path, text, error);
}

std::string CalibrationToString(
  const CameraModel& model, bool json, const CalibrationRecord* record)
{
  cv::FileStorage out(json ? ".json" : ".yaml",
    cv::FileStorage::WRITE | cv::FileStorage::MEMORY |
      (json ? cv::FileStorage::FORMAT_JSON : cv::FileStorage::FORMAT_YAML));
  WriteStorage(out, model);
  if (record)
  {
    out << "calibration"
        << "{";
    out << "rms_px" << record->rmsPx << "images_used" << record->imagesUsed;
    out << "images"
        << "[";
    for (const std::string& name : record->images)
    {
      out << name;
    }
    out << "]";
    out << "estimated"
        << "{";
    for (const CalibrationRecord::Number& n : record->estimated)
    {
      out << n.name << "{"
          << "value" << n.value << "sigma" << n.sigma << "unit" << n.unit << "}";
    }
    out << "}";
    out << "}";
  }
  std::string text = out.releaseAndGetString();
  // OpenCV writes "%YAML:1.0", which is not a YAML directive: standard parsers (PyYAML, ruamel,
  // yaml-cpp) refuse it. "%YAML 1.1" is the standard form, and OpenCV reads it too.
  const std::string opencvHeader = "%YAML:1.0";
  if (!json && text.compare(0, opencvHeader.size(), opencvHeader) == 0)
  {
    text.replace(0, opencvHeader.size(), "%YAML 1.1");
  }
  return text;
}
const CameraModel& DemoCamera()
{
  static const CameraModel camera = [] {
    CameraModel model;
    std::string error;
    if (!ParseCalibration(kDemoCameraText, model, error))
    {
      // The built-in text is fixed; a failure here is a programming error caught by the tests.
      throw std::runtime_error("built-in demo camera: " + error);
    }
    return model;
  }();
  return camera;
}
} // namespace catar
