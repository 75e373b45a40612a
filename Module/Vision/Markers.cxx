#include "Markers.h"

#include "ConfigReader.h"

#include <Eigen/Geometry>
#include <opencv2/aruco.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

namespace catar
{
namespace
{
// The adaptive threshold's margin, in sigmas of the frame's noise (7 grey levels at least).
constexpr double kThresholdNoiseSigmas = 3.25;

// The grey frame's noise, one sigma: Immerkaer's estimate (the mean absolute response to the
// difference of two Laplacians, which cancels smooth shading and most of an edge), on every 4th
// row (about 1 ms at 1328x1048). 0.13-0.17 on POV-Ray's clean frames, 4.03 with noise of 4.0.
double NoiseSigma(const cv::Mat& grey)
{
  double sum = 0.0;
  long count = 0;
  for (int y = 1; y + 1 < grey.rows; y += 4)
  {
    const std::uint8_t* a = grey.ptr<std::uint8_t>(y - 1);
    const std::uint8_t* b = grey.ptr<std::uint8_t>(y);
    const std::uint8_t* c = grey.ptr<std::uint8_t>(y + 1);
    for (int x = 1; x + 1 < grey.cols; ++x)
    {
      const int v = a[x - 1] - 2 * a[x] + a[x + 1] - 2 * b[x - 1] + 4 * b[x] - 2 * b[x + 1] +
        c[x - 1] - 2 * c[x] + c[x + 1];
      sum += std::abs(v);
      ++count;
    }
  }
  return count > 0 ? std::sqrt(0.5 * 3.14159265358979323846) * sum / (6.0 * count) : 0.0;
}

struct DictionaryName
{
  const char* name;
  cv::aruco::PREDEFINED_DICTIONARY_NAME value;
  int cells; // bits across plus the black border
};

const DictionaryName kDictionaries[] = { { "DICT_4X4_50", cv::aruco::DICT_4X4_50, 6 },
  { "DICT_4X4_100", cv::aruco::DICT_4X4_100, 6 }, { "DICT_4X4_250", cv::aruco::DICT_4X4_250, 6 },
  { "DICT_4X4_1000", cv::aruco::DICT_4X4_1000, 6 }, { "DICT_5X5_50", cv::aruco::DICT_5X5_50, 7 },
  { "DICT_5X5_100", cv::aruco::DICT_5X5_100, 7 }, { "DICT_5X5_250", cv::aruco::DICT_5X5_250, 7 },
  { "DICT_5X5_1000", cv::aruco::DICT_5X5_1000, 7 }, { "DICT_6X6_50", cv::aruco::DICT_6X6_50, 8 },
  { "DICT_6X6_100", cv::aruco::DICT_6X6_100, 8 }, { "DICT_6X6_250", cv::aruco::DICT_6X6_250, 8 },
  { "DICT_6X6_1000", cv::aruco::DICT_6X6_1000, 8 }, { "DICT_7X7_50", cv::aruco::DICT_7X7_50, 9 },
  { "DICT_7X7_100", cv::aruco::DICT_7X7_100, 9 }, { "DICT_7X7_250", cv::aruco::DICT_7X7_250, 9 },
  { "DICT_7X7_1000", cv::aruco::DICT_7X7_1000, 9 },
  { "DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL, 7 } };

const DictionaryName* FindDictionary(const std::string& name)
{
  for (const DictionaryName& d : kDictionaries)
  {
    if (name == d.name)
    {
      return &d;
    }
  }
  return nullptr;
}

cv::Ptr<cv::aruco::Dictionary> Dictionary(const std::string& name, std::string& error)
{
  const DictionaryName* d = FindDictionary(name);
  if (!d)
  {
    error = "unknown marker dictionary '" + name + "' (DICT_4X4_50, DICT_5X5_100, DICT_6X6_250, " +
      "DICT_7X7_1000, DICT_ARUCO_ORIGINAL, ...)";
    return nullptr;
  }
  return cv::aruco::getPredefinedDictionary(d->value);
}

Vec3 Vec3Of(const fs::Node& node, const std::string& key, const Vec3& fallback)
{
  const fs::Node n = node[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  const std::vector<double> v = fs::Numbers(n, key, 3);
  return Vec3(v[0], v[1], v[2]);
}
} // namespace

std::array<Vec3, 4> BoardMarker::Corners() const
{
  const Mat3 R = RotationFromDegrees(this->rotate).toRotationMatrix();
  const double h = 0.5 * this->size;
  const Vec3 local[4] = { Vec3(-h, h, 0), Vec3(h, h, 0), Vec3(h, -h, 0), Vec3(-h, -h, 0) };
  std::array<Vec3, 4> corners;
  for (int i = 0; i < 4; ++i)
  {
    corners[i] = this->translate + R * local[i];
  }
  return corners;
}

int MarkerCells(const std::string& dictionary)
{
  const DictionaryName* d = FindDictionary(dictionary);
  return d ? d->cells : 0;
}

std::string ValidateMarkerBoard(const MarkerBoard& board)
{
  std::string error;
  const cv::Ptr<cv::aruco::Dictionary> dictionary = Dictionary(board.dictionary, error);
  if (!dictionary)
  {
    return "dictionary: " + error;
  }
  std::set<int> ids;
  for (std::size_t i = 0; i < board.markers.size(); ++i)
  {
    const BoardMarker& m = board.markers[i];
    const std::string where = "markers[" + std::to_string(i) + "]: ";
    if (m.id < 0 || m.id >= dictionary->bytesList.rows)
    {
      return where + "id " + std::to_string(m.id) + " is not in " + board.dictionary + " (0 to " +
        std::to_string(dictionary->bytesList.rows - 1) + ")";
    }
    if (!ids.insert(m.id).second)
    {
      return where + "id " + std::to_string(m.id) + " is given twice";
    }
    if (!(m.size > 0.0) || !std::isfinite(m.size))
    {
      return where + "'size' must be a positive number";
    }
    if (!m.translate.allFinite() || !m.rotate.allFinite())
    {
      return where + "'translate' and 'rotate' must be finite";
    }
  }
  return std::string();
}

// The board file's `guards` section (MarkerBoard::pose and the motion limits); absent keys keep
// the defaults.
void ReadGuards(const fs::Node& guards, MarkerBoard& board)
{
  PoseOptions& options = board.pose;
  if (guards.empty() || guards.isNone())
  {
    return;
  }
  if (!guards.isMap())
  {
    throw fs::ParseError("'guards' must be a map (max_position_sigma, max_angle_sigma, ...)");
  }
  try
  {
    fs::CheckKeys(guards,
      { "max_position_sigma", "max_angle_sigma", "min_inlier_fraction", "allow_single_marker",
        "pixel_noise_floor", "max_speed", "max_turn_rate" });
  }
  catch (const fs::ParseError& e)
  {
    throw fs::ParseError(std::string("guards: ") + e.what());
  }
  const auto positive = [&](const char* key, double fallback) {
    const double v = fs::Number(guards, key, fallback);
    if (!(v > 0.0 && std::isfinite(v)))
    {
      throw fs::ParseError(std::string("guards: '") + key + "' must be a positive number");
    }
    return v;
  };
  options.maxPositionSigma = positive("max_position_sigma", options.maxPositionSigma);
  options.maxAngleSigmaDegrees = positive("max_angle_sigma", options.maxAngleSigmaDegrees);
  options.minimumPixelSigma = positive("pixel_noise_floor", options.minimumPixelSigma);
  options.minInlierFraction = fs::Number(guards, "min_inlier_fraction", options.minInlierFraction);
  if (!(options.minInlierFraction >= 0.0 && options.minInlierFraction <= 1.0))
  {
    throw fs::ParseError("guards: 'min_inlier_fraction' must be from 0 to 1");
  }
  options.allowSingleMarker = fs::Flag(guards, "allow_single_marker", options.allowSingleMarker);
  board.maxSpeed = positive("max_speed", board.maxSpeed);
  board.maxTurnRateDegrees = positive("max_turn_rate", board.maxTurnRateDegrees);
}
bool LoadMarkerBoard(const std::string& path, MarkerBoard& board, std::string& error)
{
  fs::Node root;
  if (!fs::Parse(path, false, path, root, error))
  {
    return false;
  }
  MarkerBoard b;
  try
  {
    if (!root.isMap())
    {
      throw fs::ParseError("a marker board must be a map (dictionary, markers)");
    }
    fs::CheckKeys(root, { "dictionary", "markers", "guards" });
    b.dictionary = fs::String(root, "dictionary", b.dictionary);
    ReadGuards(root["guards"], b);
    const fs::Node markers = root["markers"];
    if (!markers.isSeq() || markers.size() == 0)
    {
      throw fs::ParseError("'markers' must be a sequence of markers");
    }
    int i = 0;
    for (const fs::Node& n : markers.items())
    {
      const std::string where = "markers[" + std::to_string(i++) + "]";
      try
      {
        if (!n.isMap())
        {
          throw fs::ParseError("must be a map");
        }
        fs::CheckKeys(n, { "id", "translate", "size", "rotate" });
        BoardMarker m;
        const double id = fs::Number(n, "id");
        if (!(id >= 0 && id == std::floor(id) && id < 1e6))
        {
          throw fs::ParseError("'id' must be a non-negative integer");
        }
        m.id = static_cast<int>(id);
        m.translate = Vec3Of(n, "translate", m.translate);
        m.size = fs::Number(n, "size");
        m.rotate = Vec3Of(n, "rotate", m.rotate);
        b.markers.push_back(m);
      }
      catch (const fs::ParseError& e)
      {
        throw fs::ParseError(where + ": " + e.what());
      }
    }
  }
  catch (const std::exception& e)
  {
    error = path + ": " + e.what();
    return false;
  }
  const std::string problem = ValidateMarkerBoard(b);
  if (!problem.empty())
  {
    error = path + ": " + problem;
    return false;
  }
  board = b;
  return true;
}

bool MarkerImage(const std::string& dictionaryName, int id, int side, int margin,
  std::vector<std::uint8_t>& grey, std::string& error)
{
  const cv::Ptr<cv::aruco::Dictionary> dictionary = Dictionary(dictionaryName, error);
  if (!dictionary)
  {
    return false;
  }
  if (id < 0 || id >= dictionary->bytesList.rows)
  {
    error = "marker id " + std::to_string(id) + " is not in " + dictionaryName;
    return false;
  }
  const int cells = MarkerCells(dictionaryName) + 2 * std::max(0, margin);
  if (side < cells || side > 8192)
  {
    error = "a marker image needs " + std::to_string(cells) + " to 8192 pixels a side";
    return false;
  }
  // The marker drawn at a whole number of pixels a cell, centred in white, then resized to side.
  const int cell = std::max(1, side / cells);
  cv::Mat marker;
  cv::aruco::drawMarker(dictionary, id, cell * MarkerCells(dictionaryName), marker, 1);
  cv::Mat canvas(cell * cells, cell * cells, CV_8UC1, cv::Scalar(255));
  marker.copyTo(canvas(cv::Rect(cell * margin, cell * margin, marker.cols, marker.rows)));
  cv::Mat out;
  cv::resize(canvas, out, cv::Size(side, side), 0, 0, cv::INTER_NEAREST);
  grey.assign(out.data, out.data + out.total());
  return true;
}

bool DetectMarkers(int width, int height, const std::uint8_t* rgba,
  const std::string& dictionaryName, bool mirrored, std::vector<MarkerDetection>& detections,
  std::string& error, std::vector<std::array<Vec2, 4>>* candidates)
{
  detections.clear();
  const cv::Ptr<cv::aruco::Dictionary> dictionary = Dictionary(dictionaryName, error);
  if (!dictionary)
  {
    return false;
  }
  if (width <= 0 || height <= 0 || !rgba)
  {
    error = "an empty frame";
    return false;
  }
  const cv::Mat frame(height, width, CV_8UC4, const_cast<std::uint8_t*>(rgba));
  cv::Mat grey;
  cv::cvtColor(frame, grey, cv::COLOR_RGBA2GRAY);
  if (mirrored)
  {
    cv::flip(grey, grey, 1);
  }
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<std::vector<cv::Point2f>> rejected;
  std::vector<int> ids;
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  // Corners from lines fitted to the contour: on markers rendered through the sphere (about 40
  // pixels wide) the corners land within 1.3 px of the exact projection of the board's corners,
  // where corner sub-pixel refinement moved them up to 5 px (drawn to neighbouring texture).
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_CONTOUR;
  // Bits read from the middle of each cell, sampled finely: a marker seen in the mirror has smooth
  // edges and slightly curved sides, and OpenCV's defaults (4 pixels a cell, 13 % of each cell's
  // side ignored) read its outer cells across the edge. On POV-Ray's anti-aliased frames
  // (BenchmarkMarkersPovRay, 6 frames of 8 markers) 43 of 48 markers are found clean and 41 with
  // blur and noise by the defaults, 44 and 43 with these; on the project's own test board
  // (Markers.FoundThroughTheMirrorWhereTheyProjectAndGiveThePose) 8 of 8 instead of 7.
  parameters->perspectiveRemovePixelPerCell = 10;
  parameters->perspectiveRemoveIgnoredMarginPerCell = 0.3;
  // The adaptive threshold's margin above the frame's noise: at OpenCV's 7 grey levels, noise of
  // sigma 4 (a real lens's, and JPEG's) breaks the thresholded frame into thousands of specks whose
  // contours cost 36-42 ms a frame against 6-9 ms clean (BenchmarkMarkersPovRay); 3.25 sigmas
  // keep the cost flat (6.7-7.6 ms) and leave a clean frame's threshold as it was.
  const double noise = NoiseSigma(grey);
  parameters->adaptiveThreshConstant = std::max(7.0, kThresholdNoiseSigmas * noise);
  try
  {
    cv::aruco::detectMarkers(grey, dictionary, corners, ids, parameters, rejected);
  }
  catch (const cv::Exception& e)
  {
    error = "marker detection failed: " + e.msg;
    return false;
  }
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    MarkerDetection d;
    d.id = ids[i];
    for (int c = 0; c < 4; ++c)
    {
      // OpenCV's corner coordinates put pixel centres at integers, as this project's pixels.
      const double x = corners[i][c].x;
      d.corners[c] = Vec2(mirrored ? width - 1 - x : x, corners[i][c].y);
    }
    detections.push_back(d);
  }
  for (std::size_t i = 0; candidates && i < rejected.size(); ++i)
  {
    std::array<Vec2, 4> quad;
    for (int c = 0; c < 4 && rejected[i].size() == 4; ++c)
    {
      const double x = rejected[i][c].x;
      quad[c] = Vec2(mirrored ? width - 1 - x : x, rejected[i][c].y);
    }
    if (rejected[i].size() == 4)
    {
      candidates->push_back(quad);
    }
  }
  return true;
}

PoseResult PoseFromMarkers(const CameraModel& camera, const MarkerBoard& board,
  const std::vector<MarkerDetection>& detections, const PoseOptions& options)
{
  std::vector<PoseObservation> observations;
  std::vector<int> observationMarker; // the board marker of each observation
  for (const MarkerDetection& d : detections)
  {
    for (const BoardMarker& m : board.markers)
    {
      if (m.id != d.id)
      {
        continue;
      }
      const std::array<Vec3, 4> world = m.Corners();
      for (int c = 0; c < 4; ++c)
      {
        observations.push_back({ d.corners[c], world[c] });
        observationMarker.push_back(m.id);
      }
    }
  }
  if (observations.empty())
  {
    PoseResult r;
    r.error = detections.empty()
      ? "no marker found in the frame"
      : "none of the " + std::to_string(detections.size()) + " markers found is on the board";
    return r;
  }
  PoseResult result = EstimatePose(camera, observations, options);
  if (result.ok && !options.allowSingleMarker)
  {
    // The markers with an inlier corner.
    std::set<int> markers;
    for (std::size_t i = 0; i < result.inliers.size(); ++i)
    {
      if (result.inliers[i])
      {
        markers.insert(observationMarker[i]);
      }
    }
    if (markers.size() < 2)
    {
      result.reliable = false;
      result.warning = "one marker alone (id " + std::to_string(*markers.begin()) +
        "): its four corners through the mirror fit poses centimetres apart nearly equally well "
        "(allowed with allowSingleMarker)" +
        (result.warning.empty() ? std::string() : "; " + result.warning);
    }
  }
  return result;
}
} // namespace catar
