/**
 * @class   vtkCatadioptricEnvironmentSource
 * @brief   synthesises a camera frame: a procedural room or a panorama seen in the mirror
 *
 * Every pixel is back-projected through the camera. Two modes:
 * - ROOM (default): where a pixel sees the mirror, the reflected ray picks up the colour of a
 *   procedural room (checkered floor, tiled walls, a window, a door, a lit ceiling); elsewhere the
 *   camera sees the room directly. The room is an axis-aligned box in world coordinates (z up).
 * - PANORAMA: the mirror reflects an equirectangular panorama at infinity (PanoramaFileName, a
 *   PNG/JPEG/... image of a real place; without a file, the procedural room rendered into a
 *   panorama from the mirror centre); pixels that do not see the mirror get BackdropColor.
 *   Panorama layout (world z up): the top row is the zenith, the image's middle column looks
 *   along +x, and longitude grows towards +y to the LEFT (column
 *   x = (0.5 - lon / 360 deg) * width - 0.5); PanoramaRotation turns it about +z.
 * Output: RGBA unsigned char vtkImageData of the camera's image size, in VTK row order. Rows are
 * computed in parallel with vtkSMPTools.
 *
 * The frame depends on the camera (image size, intrinsics, distortion, mirror and pose) and on
 * this source's parameters only. An update that finds all of them equal to those of the frame it
 * made last (the camera marked modified with nothing changed, as when only the objects or the
 * lights of a scene move) keeps that frame instead of tracing every pixel again; any change, a
 * new pose included, makes a new one.
 *
 * The camera comes from SetCamera(), or, when none is set, from CalibrationFileName, or else from
 * the panel camera (CameraImageSize, FocalLength, ..., WorldToCamera: the demo camera by default).
 */
#ifndef vtkCatadioptricEnvironmentSource_h
#define vtkCatadioptricEnvironmentSource_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"     // for member
#include "vtkImageAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkCatadioptricCamera;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricEnvironmentSource : public vtkImageAlgorithm
{
public:
  static vtkCatadioptricEnvironmentSource* New();
  vtkTypeMacro(vtkCatadioptricEnvironmentSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera (vtkCatadioptricCameraSlot.h): SetCamera (takes precedence), else
  /// SetCalibrationFileName (a YAML/JSON calibration file), else the panel camera
  /// (SetCameraImageSize, SetFocalLength, SetPrincipalPoint, SetDistortion, SetWorldToCamera: the
  /// built-in demo camera's values until changed); SetMirrorType and SetMirrorParameter put
  /// another mirror in the camera's place;
  /// SetTrajectoryFileName moves the camera over time. Each with its getter.
  vtkCatadioptricCameraSlotDeclareMacro();
  vtkCatadioptricCameraSlotDeclareTrajectoryMacro();
  ///@}

  ///@{
  /// Supersampling: Samples x Samples rays per pixel (1 to 8). Default 2.
  vtkSetClampMacro(Samples, int, 1, 8);
  vtkGetMacro(Samples, int);
  ///@}

  ///@{
  /// The room: its two opposite corners (world coordinates) and the floor tile size.
  vtkSetVector3Macro(RoomMinimum, double);
  vtkGetVector3Macro(RoomMinimum, double);
  vtkSetVector3Macro(RoomMaximum, double);
  vtkGetVector3Macro(RoomMaximum, double);
  vtkSetClampMacro(FloorTileSize, double, 1e-6, 1e6);
  vtkGetMacro(FloorTileSize, double);
  ///@}

  /// What the frame shows.
  enum Modes
  {
    ROOM = 0,    ///< the procedural room, in and around the mirror (default)
    PANORAMA = 1 ///< a panorama at infinity in the mirror, BackdropColor around it
  };

  ///@{
  /// ROOM (default) or PANORAMA.
  vtkSetClampMacro(Mode, int, ROOM, PANORAMA);
  vtkGetMacro(Mode, int);
  void SetModeToRoom() { this->SetMode(ROOM); }
  void SetModeToPanorama() { this->SetMode(PANORAMA); }
  ///@}

  ///@{
  /// PANORAMA mode: an equirectangular image file (any format OpenCV's imread reads: PNG,
  /// JPEG, TIFF, BMP, ...; grey, RGB or RGBA, 8 or 16 bits; float images such as Radiance .hdr
  /// are tone-mapped with c / (1 + c) and gamma 2.2). It is read once and kept until the name or
  /// the file's modification time changes (after rewriting the file under the same name, call
  /// Modified() so that the pipeline updates). A missing or unreadable file is an error (the
  /// update fails, nothing crashes). Null or "" (default): the room of RoomMinimum /
  /// RoomMaximum / FloorTileSize rendered into a 2048x1024 panorama from the mirror centre.
  vtkSetStringMacro(PanoramaFileName);
  vtkGetStringMacro(PanoramaFileName);
  ///@}

  ///@{
  /// PANORAMA mode: rotation of the panorama about the world +z axis, degrees (its middle column
  /// then looks along longitude PanoramaRotation, counter-clockwise from +x). Default 0. NaN and
  /// infinite values are refused (an error; the rotation is left as it was).
  virtual void SetPanoramaRotation(double degrees);
  vtkGetMacro(PanoramaRotation, double);
  ///@}

  ///@{
  /// PANORAMA mode: colour (RGB in [0,1]) of the pixels that do not see the mirror. Default mid
  /// grey (0.5, 0.5, 0.5).
  vtkSetVector3Macro(BackdropColor, double);
  vtkGetVector3Macro(BackdropColor, double);
  ///@}

  /// The modification time includes the camera's.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricEnvironmentSource();
  ~vtkCatadioptricEnvironmentSource() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Brings the cached panorama of PANORAMA mode up to date (read or generated); false after an
  /// error (reported).
  bool UpdatePanorama(vtkCatadioptricCamera* camera);

  vtkCatadioptricCameraSlotMembersMacro();
  int Samples = 2;
  double RoomMinimum[3] = { -2.0, -2.0, 0.0 };
  double RoomMaximum[3] = { 2.0, 2.0, 2.6 };
  double FloorTileSize = 0.25;
  int Mode = ROOM;
  char* PanoramaFileName = nullptr;
  double PanoramaRotation = 0.0;
  double BackdropColor[3] = { 0.5, 0.5, 0.5 };

private:
  struct PanoramaCache;
  std::unique_ptr<PanoramaCache> Cache;
  struct FrameCache;
  std::unique_ptr<FrameCache> LastFrame;

  vtkCatadioptricEnvironmentSource(const vtkCatadioptricEnvironmentSource&) = delete;
  void operator=(const vtkCatadioptricEnvironmentSource&) = delete;
};

#endif
