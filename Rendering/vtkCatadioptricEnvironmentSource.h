/**
 * @class   vtkCatadioptricEnvironmentSource
 * @brief   synthesises a camera frame: a procedural room seen in (and around) the mirror
 *
 * Every pixel is back-projected through the camera: where it sees the mirror, the reflected ray
 * picks up the colour of a procedural room (checkered floor, tiled walls, a window, a door, a lit
 * ceiling); elsewhere the camera sees the room directly. The room is an axis-aligned box in world
 * coordinates (z up). Output: RGBA unsigned char vtkImageData of the camera's image size, in VTK
 * row order. Rows are computed in parallel with vtkSMPTools.
 *
 * The camera comes from SetCamera(), or, when none is set, from CalibrationFileName.
 */
#ifndef vtkCatadioptricEnvironmentSource_h
#define vtkCatadioptricEnvironmentSource_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"     // for member
#include "vtkImageAlgorithm.h"

class vtkCatadioptricCamera;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricEnvironmentSource : public vtkImageAlgorithm
{
public:
  static vtkCatadioptricEnvironmentSource* New();
  vtkTypeMacro(vtkCatadioptricEnvironmentSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera. Takes precedence over CalibrationFileName.
  void SetCamera(vtkCatadioptricCamera* camera);
  vtkCatadioptricCamera* GetCamera();
  ///@}

  ///@{
  /// A calibration file (YAML/JSON) to use when no camera object is set.
  void SetCalibrationFileName(const char* fileName);
  const char* GetCalibrationFileName();
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

  /// The modification time includes the camera's.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricEnvironmentSource();
  ~vtkCatadioptricEnvironmentSource() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  vtkCatadioptricCamera* ResolveCamera();

  vtkCatadioptricCameraSlot CameraSlot;
  int Samples = 2;
  double RoomMinimum[3] = { -2.0, -2.0, 0.0 };
  double RoomMaximum[3] = { 2.0, 2.0, 2.6 };
  double FloorTileSize = 0.25;

private:
  vtkCatadioptricEnvironmentSource(const vtkCatadioptricEnvironmentSource&) = delete;
  void operator=(const vtkCatadioptricEnvironmentSource&) = delete;
};

#endif
