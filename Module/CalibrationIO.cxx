#include "CalibrationIO.h"

#include "FileOutput.h"
#include "FileStorageUtil.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
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
    // rows x cols must be what data holds before OpenCV allocates them (a lying size would
    // reserve gigabytes).
    const cv::FileNode rows = node["rows"], cols = node["cols"], data = node["data"];
    if (!rows.isInt() || !cols.isInt() || !data.isSeq() || static_cast<int>(rows) < 1 ||
      static_cast<int>(cols) < 1 ||
      static_cast<double>(static_cast<int>(rows)) * static_cast<int>(cols) !=
        static_cast<double>(data.size()))
    {
      throw ParseError("'" + key + "': the matrix's rows x cols must match its data");
    }
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

namespace
{
// Edit distance (insertions, deletions, substitutions), for key suggestions.
std::size_t EditDistance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
  {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t up = row[j];
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1) });
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The deepest nesting of `text`: flow brackets ([ {) outside quotes and comments, plus the
// levels of block indentation (a stack of increasing indents, "- " items counting as one more).
int Nesting(const std::string& text)
{
  int deepest = 0;
  int brackets = 0;
  std::vector<std::size_t> indents;
  std::size_t pos = 0;
  while (pos < text.size())
  {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos)
    {
      end = text.size();
    }
    // Block indentation of the line (blank and comment lines do not count).
    std::size_t indent = pos;
    while (indent < end && (text[indent] == ' ' || text[indent] == '-'))
    {
      ++indent;
    }
    if (indent < end && text[indent] != '#' && text[indent] != '\r' && brackets == 0)
    {
      const std::size_t column = indent - pos;
      while (!indents.empty() && indents.back() > column)
      {
        indents.pop_back();
      }
      if (indents.empty() || indents.back() < column)
      {
        indents.push_back(column);
      }
    }
    // "- - - x" nests sequences on one line.
    int dashes = 0;
    for (std::size_t k = pos; k < indent; ++k)
    {
      dashes += text[k] == '-';
    }
    char quote = 0;
    for (std::size_t k = pos; k < end; ++k)
    {
      const char c = text[k];
      if (quote)
      {
        quote = c == quote ? 0 : quote;
      }
      else if (c == '"' || c == '\'')
      {
        quote = c;
      }
      else if (c == '#')
      {
        break;
      }
      else if (c == '[' || c == '{')
      {
        deepest = std::max(deepest, static_cast<int>(indents.size()) + dashes + ++brackets);
      }
      else if ((c == ']' || c == '}') && brackets > 0)
      {
        --brackets;
      }
    }
    deepest = std::max(deepest, static_cast<int>(indents.size()) + dashes);
    pos = end + 1;
  }
  return deepest;
}
} // namespace

void CheckKeys(const cv::FileNode& node, std::initializer_list<const char*> known)
{
  if (!node.isMap())
  {
    return;
  }
  for (const std::string& key : node.keys())
  {
    if (std::find_if(known.begin(), known.end(), [&](const char* k) { return key == k; }) !=
      known.end())
    {
      continue;
    }
    std::string message = "unknown key '" + key + "'";
    const char* nearest = nullptr;
    std::size_t best = std::max<std::size_t>(2, key.size() / 3) + 1;
    for (const char* k : known)
    {
      const std::size_t d = EditDistance(key, k);
      if (d < best)
      {
        best = d;
        nearest = k;
      }
    }
    if (nearest)
    {
      message += std::string(" (did you mean '") + nearest + "'?)";
    }
    else
    {
      message += " (known keys:";
      for (const char* k : known)
      {
        message += std::string(" ") + k;
      }
      message += ")";
    }
    throw ParseError(message);
  }
}

bool OpenStorage(cv::FileStorage& storage, const std::string& source, bool isText,
  const std::string& what, std::string& error)
{
  std::string text;
  if (isText)
  {
    text = source;
  }
  else
  {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(source, ec))
    {
      error = what + ": cannot open the file (" +
        (ec ? ec.message() : std::string("not a regular file")) + ")";
      return false;
    }
    std::ifstream in(source, std::ios::binary);
    if (!in)
    {
      error = what + ": cannot open the file";
      return false;
    }
    try
    {
      text.resize(kMaxTextBytes + 1);
      in.read(&text[0], static_cast<std::streamsize>(text.size()));
      text.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    }
    catch (const std::exception& e)
    {
      error = what + ": cannot read the file (" + e.what() + ")";
      return false;
    }
  }
  if (text.size() > kMaxTextBytes)
  {
    error = what + ": larger than the limit of " + std::to_string(kMaxTextBytes) + " bytes";
    return false;
  }
  const int depth = Nesting(text);
  if (depth > kMaxNesting)
  {
    error = what + ": nested " + std::to_string(depth) + " levels deep (at most " +
      std::to_string(kMaxNesting) + ")";
    return false;
  }
  try
  {
    if (!storage.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY))
    {
      error = what + ": cannot be parsed as YAML or JSON";
      return false;
    }
  }
  catch (const cv::Exception& e)
  {
    error = what + ": not a valid YAML/JSON file (" + e.msg + ")";
    return false;
  }
  catch (const std::exception& e) // the parser throws std::length_error on some broken files
  {
    error = what + ": not a valid YAML/JSON file (" + e.what() + ")";
    return false;
  }
  return true;
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
  return fs::OpenStorage(storage, path, false, path, error) &&
    ReadStorage(storage, path, model, error);
}

bool ParseCalibration(const std::string& text, CameraModel& model, std::string& error)
{
  cv::FileStorage storage;
  return fs::OpenStorage(storage, text, true, "calibration text", error) &&
    ReadStorage(storage, "calibration text", model, error);
}

bool SaveCalibration(const std::string& path, const CameraModel& model, std::string& error)
{
  const std::string problem = model.Validate();
  if (!problem.empty())
  {
    error = "refusing to save an invalid camera: " + problem;
    return false;
  }
  // Made in memory (the format follows the extension, as cv::FileStorage decides it), then
  // written with every error checked: cv::FileStorage reports none of a full disk.
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  const bool hasExt = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string ext = hasExt ? path.substr(dot) : std::string(".yaml");
  std::string text;
  try
  {
    cv::FileStorage out(ext, cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    if (!out.isOpened())
    {
      error = path + ": cannot write a calibration in this format (.yaml, .yml, .json, .xml)";
      return false;
    }
    WriteStorage(out, model);
    text = out.releaseAndGetString();
  }
  catch (const cv::Exception& e)
  {
    error = path + ": " + e.msg;
    return false;
  }
  return WriteWholeFile(path, text, error);
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
