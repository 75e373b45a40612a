/**
 * @class   vtkCatadioptricRigSource
 * @brief   the rig in 3D: the camera centre, its lens frustum and the mirror it sees, world frame
 *
 * Polydata in world coordinates, to show beside the scene where the camera and the mirror are.
 * Cell data `RigPart` (int, RigParts) says which part each cell draws:
 * - CAMERA_CENTRE (0): a vertex at the camera centre, -R^T t of the world-to-camera pose;
 * - FRUSTUM (1): lines from the centre to the image's four corners (pixels (-0.5, -0.5) to
 *   (width - 0.5, height - 0.5), the outer edges of the corner pixels) back-projected through the
 *   lens alone (intrinsics and distortion, not the mirror) to the depth FrustumLength, and a closed
 *   line along the image border at that depth (curved when the lens distorts);
 * - MIRROR (2): triangles on the part of the mirror the camera sees, with point normals facing the
 *   camera. A grid of pixels over the mirror's image (MirrorResolution cells along its longer side)
 *   is back-projected and met with the mirror; where the mirror's image ends inside a cell, the
 *   boundary point is found by bisection along the cell's edge. Every point lies on the mirror (to
 *   its intersection accuracy), inside its bounds, and is the point seen at its pixel;
 * - MIRROR_OUTLINE (3): closed lines along the boundary of those triangles: the mirror's rim as the
 *   camera sees it (the image border where the frame cuts the mirror). Only with MirrorOutline on.
 * The camera travels as field data too (vtkCatadioptricCamera::WriteToFieldData).
 *
 * The camera comes from SetCamera(), or, when none is set, from CalibrationFileName, or else from
 * the panel camera (CameraImageSize, FocalLength, ..., WorldToCamera: the demo camera by default);
 * a TrajectoryFileName moves it over time as in vtkCatadioptricEnvironmentSource. An unusable
 * camera is an error (the update fails, the output is empty).
 */
#ifndef vtkCatadioptricRigSource_h
#define vtkCatadioptricRigSource_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"     // for member
#include "vtkPolyDataAlgorithm.h"

class vtkCatadioptricCamera;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricRigSource : public vtkPolyDataAlgorithm
{
public:
  static vtkCatadioptricRigSource* New();
  vtkTypeMacro(vtkCatadioptricRigSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The values of the cell-data array RigPart.
  enum RigParts
  {
    CAMERA_CENTRE = 0, ///< a vertex at the camera centre
    FRUSTUM = 1,       ///< the lens frustum's lines
    MIRROR = 2,        ///< the mirror's triangles
    MIRROR_OUTLINE = 3 ///< the mirror's rim as the camera sees it
  };

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
  /// Depth (camera-frame z, the unit of the calibration) of the frustum's far end. 0 (the
  /// default) or less: 1.25 times the depth of the farthest mirror point seen, a little beyond
  /// the mirror. NaN and infinite values are refused (an error; the length is left as it was).
  virtual void SetFrustumLength(double length);
  vtkGetMacro(FrustumLength, double);
  ///@}

  ///@{
  /// Grid cells along the longer side of the part of the image that shows the mirror: the
  /// mirror's triangles are about that many across (2 to 1024). Default 48.
  vtkSetClampMacro(MirrorResolution, int, 2, 1024);
  vtkGetMacro(MirrorResolution, int);
  ///@}

  ///@{
  /// Points per image side on the frustum's far border when the lens distorts (1 to 1024; without
  /// distortion the border is the four corners). Default 16.
  vtkSetClampMacro(BorderResolution, int, 1, 1024);
  vtkGetMacro(BorderResolution, int);
  ///@}

  ///@{
  /// Whether the output has the mirror's outline (RigPart MIRROR_OUTLINE). Default on.
  vtkSetMacro(MirrorOutline, vtkTypeBool);
  vtkGetMacro(MirrorOutline, vtkTypeBool);
  vtkBooleanMacro(MirrorOutline, vtkTypeBool);
  ///@}

  /// The depth the last update gave the frustum (FrustumLength, or the automatic one).
  vtkGetMacro(FrustumLengthUsed, double);

  /// The modification time includes the camera's.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricRigSource();
  ~vtkCatadioptricRigSource() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkCatadioptricCameraSlotMembersMacro();
  double FrustumLength = 0.0;
  int MirrorResolution = 48;
  int BorderResolution = 16;
  vtkTypeBool MirrorOutline = 1;
  double FrustumLengthUsed = 0.0;

private:
  vtkCatadioptricRigSource(const vtkCatadioptricRigSource&) = delete;
  void operator=(const vtkCatadioptricRigSource&) = delete;
};

#endif
