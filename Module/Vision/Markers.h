// CatadioptricAR Core: fiducial markers (ArUco, OpenCV) seen through the mirror, for the pose of
// each frame (PoseEstimation.h).
//
// A marker board file (YAML or JSON) gives the markers' layout in the world:
//   dictionary: DICT_4X4_50          # an OpenCV predefined ArUco dictionary
//   markers:
//     - { id: 0, translate: [ 0.3, -0.2, 0.0 ], size: 0.12, rotate: [ 0, 0, 0 ] }
// `size` is the side of the black square (metres); `rotate` turns the marker (printed in its own
// x-y plane, x to the right, y up, seen from +z) by degrees about x, then y, then z, as a scene
// object's `rotate`; a marker with no rotate lies flat, facing +z (up). The same keys make a
// `marker` object in a scene, so one layout serves the scene that draws the markers and the
// board that finds them.
//
// A convex mirror shows a marker mirror-imaged; DetectMarkers looks for them in the flipped frame
// and maps the corners back.
#ifndef catarMarkers_h
#define catarMarkers_h

#include "CameraModel.h"
#include "PoseEstimation.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace catar
{
struct BoardMarker
{
  int id = 0;
  Vec3 translate = Vec3::Zero(); ///< the marker's centre in the world
  double size = 0.1;
  Vec3 rotate = Vec3::Zero(); ///< degrees about x, then y, then z
  /// The corners in the world, in OpenCV's order: the printed marker's top-left, top-right,
  /// bottom-right, bottom-left.
  std::array<Vec3, 4> Corners() const;
};

struct MarkerBoard
{
  std::string dictionary = "DICT_4X4_50";
  std::vector<BoardMarker> markers;
  /// The pose estimation's options, its guards from the file's `guards` section:
  ///   guards: { max_position_sigma: 0.008, max_angle_sigma: 0.4, min_inlier_fraction: 0.5,
  ///             allow_single_marker: false, pixel_noise_floor: 0.5, max_speed: 5,
  ///             max_turn_rate: 360 }
  /// (metres, degrees, a fraction, a boolean, pixels; PoseOptions).
  PoseOptions pose;
  /// From frame to frame (MarkerPoseTracker.h): how far the camera may move between two frames'
  /// poses, from the same section: max_speed (m/s), max_turn_rate (degrees/s).
  double maxSpeed = 5.0;
  double maxTurnRateDegrees = 360.0;
};

/// Reads a board file; false with a sentence naming the key (an unknown dictionary, an id the
/// dictionary does not have, an id given twice, a size not positive, a guard out of range, ...).
bool LoadMarkerBoard(const std::string& path, MarkerBoard& board, std::string& error);
/// "" when the dictionary is one of OpenCV's predefined ones and every id is in it, else a
/// sentence.
std::string ValidateMarkerBoard(const MarkerBoard& board);

/// A marker as an image to print or texture: side x side grey pixels (8 bits), the marker's
/// black square and bits with a white margin of `margin` bit cells around it. False with a
/// sentence for an unknown dictionary or id.
bool MarkerImage(const std::string& dictionary, int id, int side, int margin,
  std::vector<std::uint8_t>& grey, std::string& error);
/// The number of bit cells across a marker of the dictionary, its black border included
/// (6 for the 4x4 dictionaries); 0 for an unknown dictionary.
int MarkerCells(const std::string& dictionary);

struct MarkerDetection
{
  int id = 0;
  std::array<Vec2, 4> corners; ///< pixels, in the order of BoardMarker::Corners
};

/// The markers of `dictionary` in an RGBA8 frame (top row first). mirrored: look in the
/// left-right flipped frame (markers seen in a convex mirror), corners mapped back. Corners
/// from lines fitted to each marker's contour (RefineMarkerCorners then puts them on the edges).
/// The adaptive threshold keeps pixels darker than their neighbourhood by 3.25 sigmas of the
/// frame's noise (estimated from it), 7 grey levels at least, so that a noisy frame costs what a
/// clean one does. False with a sentence for an unknown dictionary or an empty frame; no markers
/// is not an error.
bool DetectMarkers(int width, int height, const std::uint8_t* rgba, const std::string& dictionary,
  bool mirrored, std::vector<MarkerDetection>& detections, std::string& error,
  std::vector<std::array<Vec2, 4>>* candidates = nullptr);
// `candidates`, when given, receives the quadrilaterals that were found but not decoded (pixels,
// mapped back as the markers' corners are), for RecoverMarkers.

/// Markers of the board that DetectMarkers found as quadrilaterals but could not decode, recovered
/// where a pose puts them: `camera` (with that pose) projects each missing marker's corners and
/// the centres of its bit cells through the mirror; a candidate whose corners lie within a quarter
/// of the marker's shorter side (3 px at least) of the projected ones, and whose cells sampled at
/// the projected centres read the marker's border and bits (at most one of the inner bits wrong,
/// two of the border's), is added to `detections` with its own corners (refined to sub-pixel), in
/// the marker's order.
/// A marker seen through a mirror near its rim has curved sides, and OpenCV reads its bits
/// through a plane's homography: that is where decoding fails. A missing marker that no candidate
/// matches (a small one in a noisy frame, whose contours break up) is searched for again in the
/// region around its predicted image (half its longer side more), enlarged to about 60 px a
/// side; what is found there is matched and read in the same way. Markers predicted under 10 px
/// on their shorter side are not looked for. Returns the number added.
int RecoverMarkers(int width, int height, const std::uint8_t* rgba, const CameraModel& camera,
  const MarkerBoard& board, const std::vector<std::array<Vec2, 4>>& candidates,
  std::vector<MarkerDetection>& detections);

/// The detected markers' corners moved onto the edges of their black squares: along each side
/// the grey level's half-way crossing from the black square to the white margin, sampled across
/// the side every pixel, a line fitted to them on top of the side's curvature, which `camera`
/// (posed near the truth: this frame's first pose or the last one) gives by projecting the
/// board's marker through the mirror; the corners where adjacent sides meet. OpenCV's corners
/// come from straight lines through a thresholded contour's pixels: they lie about half a pixel
/// inside the edges, and a mirror bends the sides. A marker whose corners the pose projects more
/// than a tenth of its shorter side (2 px at least) from where they were found is left as it is;
/// so is a corner when a side shows too few crossings or the corner would move more than 2 px.
/// Returns the number of corners moved.
int RefineMarkerCorners(int width, int height, const std::uint8_t* rgba, const CameraModel& camera,
  const MarkerBoard& board, std::vector<MarkerDetection>& detections);

/// The pose from the detected markers of the board (their four corners each): EstimatePose on
/// the corners of the markers the board has. result.error says why when it fails (no marker of
/// the board detected, or EstimatePose's reasons).
PoseResult PoseFromMarkers(const CameraModel& camera, const MarkerBoard& board,
  const std::vector<MarkerDetection>& detections, const PoseOptions& options = {});
} // namespace catar

#endif
