// CatadioptricAR Core: calibration files (YAML or JSON, read with yaml-cpp; written as OpenCV
// FileStorage writes them, so OpenCV reads them too, but with the standard `%YAML 1.1` directive).
//
// The format (Documentation/opencv-calibration.md): image_width, image_height, camera_matrix (3x3),
// lens (pinhole, the default, or fisheye; or ROS's distortion_model), distortion_coefficients
// (pinhole: OpenCV's 4, 5, 8, 12 or 14 numbers; fisheye: k1 k2 k3 k4), mirror {type: sphere,
// center [x y z] in the camera frame, radius}, world_to_camera (4x4). Matrices may be written as
// OpenCV matrices
// (!!opencv-matrix) or as plain sequences (row-major).
#ifndef catarCalibrationIO_h
#define catarCalibrationIO_h

#include "CameraModel.h"

#include <string>
#include <vector>

namespace catar
{
/// Reads a calibration file. On failure returns false and says why in `error` (file name and the
/// offending key); `model` is left unchanged.
bool LoadCalibration(const std::string& path, CameraModel& model, std::string& error);

/// LoadCalibration for a file that may describe the lens alone (OpenCV's calibration of the bare
/// camera: no `mirror`): the model keeps its own mirror then. For the tools that find the mirror.
bool LoadLensCalibration(const std::string& path, CameraModel& model, std::string& error);

/// Reads a calibration given as text (YAML or JSON), for embedding. Same rules as LoadCalibration.
bool ParseCalibration(const std::string& text, CameraModel& model, std::string& error);

/// What a calibration of the rig from images adds to its file (catadioptric-calibrate): the
/// `calibration` map, which readers read past.
///   calibration:
///     rms_px: 0.12            # the corners' reprojection error through the calibrated rig
///     images_used: 10
///     images: [ a.png, ... ]  # the views used
///     estimated: { radius: { value: 0.05, sigma: 2e-5, unit: m }, ... }
struct CalibrationRecord
{
  struct Number
  {
    std::string name;
    std::string unit;
    double value = 0.0;
    double sigma = 0.0;
  };
  double rmsPx = 0.0;
  int imagesUsed = 0;
  std::vector<std::string> images;
  std::vector<Number> estimated;
};

/// Writes a calibration file; the format follows the extension (.yaml/.yml or .json). With a
/// record, its `calibration` map too.
bool SaveCalibration(const std::string& path, const CameraModel& model, std::string& error,
  const CalibrationRecord* record = nullptr);

/// The built-in demo camera: Data/calibration/demo-camera.yaml, embedded when the project is
/// configured (the demo scene's camera; the VTK camera's defaults). Parsed once.
const CameraModel& DemoCamera();

/// The calibration as YAML (or JSON) text (with the record's map, when given).
std::string CalibrationToString(
  const CameraModel& model, bool json = false, const CalibrationRecord* record = nullptr);
} // namespace catar

#endif
