// CatadioptricAR Core (private): the marker functions on a frame's grey image, so that a tracker
// converts its frame once (MarkerRecovery.cxx, MarkerCorners.cxx). Not installed.
#ifndef catarMarkerGrey_h
#define catarMarkerGrey_h

#include "Markers.h"

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace catar
{
namespace detail
{
/// The grey image (8-bit, one channel) of a width x height RGBA8 frame.
cv::Mat GreyOf(int width, int height, const std::uint8_t* rgba);

/// The grey level at a pixel (bilinear; pixel centres at integers, as OpenCV's); -1 outside the
/// image.
double GreyAt(const cv::Mat& grey, const Vec2& p);

/// RecoverMarkers and RefineMarkerCorners (Markers.h) on the frame's grey image.
int RecoverMarkers(const cv::Mat& grey, const CameraModel& camera, const MarkerBoard& board,
  const std::vector<std::array<Vec2, 4>>& candidates, std::vector<MarkerDetection>& detections);
int RefineMarkerCorners(const cv::Mat& grey, const CameraModel& camera, const MarkerBoard& board,
  std::vector<MarkerDetection>& detections);
} // namespace detail
} // namespace catar

#endif
