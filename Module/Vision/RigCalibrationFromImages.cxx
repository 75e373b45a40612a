// CalibrateRigFromImages: the board's corners found in the images, then CalibrateRig twice (before
// and after the corners are put on the markers' edges with the calibrated rig).
#include "RigCalibration.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace catar
{
namespace
{
// The view of an image's detections: each detected marker of the board gives its four corners.
CalibrationView ViewOf(
  const std::string& name, const MarkerBoard& board, const std::vector<MarkerDetection>& detections)
{
  std::map<int, const BoardMarker*> byId;
  for (const BoardMarker& m : board.markers)
  {
    byId[m.id] = &m;
  }
  CalibrationView view;
  view.name = name;
  for (const MarkerDetection& d : detections)
  {
    const auto found = byId.find(d.id);
    if (found == byId.end())
    {
      continue;
    }
    const auto corners = found->second->Corners();
    for (int c = 0; c < 4; ++c)
    {
      PoseObservation o;
      o.pixel = d.corners[static_cast<std::size_t>(c)];
      o.world = corners[static_cast<std::size_t>(c)];
      view.observations.push_back(o);
    }
  }
  return view;
}
} // namespace

CalibrationRecord RecordOf(const CalibrationResult& result, const std::vector<std::string>& names)
{
  CalibrationRecord record;
  record.rmsPx = result.rmsPixels;
  record.imagesUsed = result.imagesUsed;
  for (const int v : result.usedViews)
  {
    record.images.push_back(names.at(static_cast<std::size_t>(v)));
  }
  for (const auto* list : { &result.mirror, &result.lens })
  {
    for (const CalibratedNumber& n : *list)
    {
      record.estimated.push_back({ n.name, n.unit, n.value, n.sigma });
    }
  }
  return record;
}

CalibrationResult CalibrateRigFromImages(const CameraModel& initial, const MarkerBoard& board,
  const std::vector<CalibrationImage>& images, const CalibrationOptions& options,
  std::vector<CalibrationView>* viewsOut)
{
  CalibrationResult out;
  if (const std::string why = ValidateMarkerBoard(board); !why.empty())
  {
    out.error = "the board is not usable: " + why;
    return out;
  }
  const int w = initial.intrinsics.width;
  const int h = initial.intrinsics.height;
  std::vector<std::vector<MarkerDetection>> detections(images.size());
  std::vector<CalibrationView> views;
  for (std::size_t i = 0; i < images.size(); ++i)
  {
    const CalibrationImage& image = images[i];
    if (image.width != w || image.height != h || !image.rgba)
    {
      out.error = "the image '" + image.name + "' is " + std::to_string(image.width) + " x " +
        std::to_string(image.height) + " pixels but the calibration is for " + std::to_string(w) +
        " x " + std::to_string(h);
      return out;
    }
    std::string error;
    if (!DetectMarkers(w, h, image.rgba, board.dictionary, true, detections[i], error))
    {
      out.error = "the image '" + image.name + "': " + error;
      return out;
    }
    views.push_back(ViewOf(image.name, board, detections[i]));
  }
  // Twice: the corners on the edges with the calibrated rig and each view's board pose, and the
  // calibration again (the second pass starts from corners the first already moved, with a rig
  // closer to the truth, so that more markers pass RefineMarkerCorners' checks).
  // The first passes' corners are OpenCV's (biased): only the last pass is held to the
  // options' bounds on the fit.
  CalibrationOptions loose = options;
  loose.maxRmsPixels = std::max(options.maxRmsPixels, 10.0);
  loose.maxSizeChange = std::max(options.maxSizeChange, 0.5);
  out = CalibrateRig(initial, views, loose);
  for (int pass = 0; pass < 2 && out.ok; ++pass)
  {
    for (std::size_t k = 0; k < out.usedViews.size(); ++k)
    {
      const std::size_t i = static_cast<std::size_t>(out.usedViews[k]);
      CameraModel posed = out.camera;
      posed.worldToCamera = out.boardToCamera[k];
      RefineMarkerCorners(w, h, images[i].rgba, posed, board, detections[i]);
      views[i] = ViewOf(images[i].name, board, detections[i]);
    }
    out = CalibrateRig(initial, views, pass == 1 ? options : loose);
  }
  if (viewsOut)
  {
    *viewsOut = views;
  }
  return out;
}
} // namespace catar
