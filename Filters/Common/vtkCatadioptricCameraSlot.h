/**
 * @class   vtkCatadioptricCameraSlot
 * @brief   where a filter or source gets its camera: an object, or a calibration file
 *
 * Not a vtkObject: a member of the algorithms that need a camera
 * (vtkCatadioptricProjection, vtkCatadioptricEnvironmentSource, ...). The camera object takes
 * precedence; otherwise the calibration file is loaded, once per file name, into a private
 * camera; with neither, the camera is made from the panel's values (image size, focal length,
 * principal point, distortion, world-to-camera), which are the built-in demo camera's
 * (Data/calibration/demo-camera.yaml) until changed, so a ParaView pipeline draws on its first
 * Apply. C++ only (not wrapped).
 */
#ifndef vtkCatadioptricCameraSlot_h
#define vtkCatadioptricCameraSlot_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "vtkSmartPointer.h"            // for members
#include "vtkType.h"                    // for vtkMTimeType

#include <memory> // for members
#include <string> // for members
#include <vector> // for members

class vtkCatadioptricCamera;
class vtkInformation;
namespace catar
{
struct Trajectory;
}

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricCameraSlot
{
public:
  vtkCatadioptricCameraSlot();
  ~vtkCatadioptricCameraSlot();

  /// Set the camera object; returns true when it changed.
  bool SetCamera(vtkCatadioptricCamera* camera);
  vtkCatadioptricCamera* GetCamera() const;

  /// Set the calibration file name (null or "" for none); returns true when it changed.
  bool SetCalibrationFileName(const char* fileName);
  /// The file name, or null when none is set.
  const char* GetCalibrationFileName() const;

  /// The panel's camera, used without a camera object and a calibration file; setters return true
  /// when they changed something. Values are checked when the camera is made (Resolve), where a
  /// bad one is an error that names the panel property.
  bool SetCameraImageSize(int width, int height);
  bool SetFocalLength(double fx, double fy);
  bool SetPrincipalPoint(double cx, double cy);
  bool SetDistortion(const double coefficients[5]); ///< k1, k2, p1, p2, k3 (OpenCV's order)
  bool SetWorldToCamera(const double elements[16]); ///< row-major
  void GetCameraImageSize(int size[2]) const;
  void GetFocalLength(double f[2]) const;
  void GetPrincipalPoint(double c[2]) const;
  void GetDistortion(double coefficients[5]) const;
  void GetWorldToCamera(double elements[16]) const;

  /// The camera object's modification time (0 without one).
  vtkMTimeType GetCameraMTime() const;

  /// A mirror in place of the camera's (for ParaView's panel): a type ("" for the camera's own)
  /// and its numbers. Setters return true when they changed something.
  /// "from calibration" is the same as "": keep the camera's own mirror (ParaView's panel shows
  /// it).
  bool SetMirrorType(const char* type);
  static constexpr const char* kMirrorFromCalibration = "from calibration";
  const char* GetMirrorType() const { return this->MirrorType.c_str(); }
  bool SetNumberOfMirrorParameters(int n);
  bool SetMirrorParameter(int i, double value);
  int GetNumberOfMirrorParameters() const
  {
    return static_cast<int>(this->MirrorParameters.size());
  }
  double GetMirrorParameter(int i) const;

  /// A trajectory file (Documentation/file-formats.md: TUM or matrix poses; null or "" for none);
  /// returns true when it changed. With one, the camera's pose is the trajectory's at the time the
  /// pipeline asks for.
  bool SetTrajectoryFileName(const char* fileName);
  const char* GetTrajectoryFileName() const;

  /// In an algorithm's RequestInformation: with a trajectory, its poses' times as the output's
  /// TIME_STEPS and TIME_RANGE (so ParaView's animation plays them); without one, removes both.
  /// False with a sentence in error when the file cannot be read.
  bool AnnounceTimeSteps(vtkInformation* outInfo, std::string& error);

  /// The camera to use now: the object if set, else the one loaded from the file; with the mirror
  /// replaced when a mirror type is set; with a trajectory, at the pose of the time outInfo asks
  /// for (UPDATE_TIME_STEP; the first pose when it asks for none). Returns nullptr and says why
  /// in `error` when neither gives a camera, the mirror is not a usable one of its type, or the
  /// trajectory cannot be read.
  vtkCatadioptricCamera* Resolve(std::string& error, vtkInformation* outInfo = nullptr);

private:
  vtkCatadioptricCamera* ResolveBase(std::string& error);
  vtkCatadioptricCamera* ResolveMirror(std::string& error);
  const catar::Trajectory* LoadTrajectory(std::string& error);

  std::string TrajectoryName;
  std::string LoadedTrajectoryName;
  std::shared_ptr<catar::Trajectory> LoadedTrajectory;
  vtkSmartPointer<vtkCatadioptricCamera> TimedCamera; // the camera at the asked time's pose
  vtkCatadioptricCamera* TimedCameraFrom = nullptr;
  vtkMTimeType TimedCameraBase = 0;
  double TimedCameraTime = 0.0;

  vtkCatadioptricCamera* ResolvePanel(std::string& error);

  int PanelImageSize[2];
  double PanelFocalLength[2];
  double PanelPrincipalPoint[2];
  double PanelDistortion[5];
  double PanelWorldToCamera[16];
  bool PanelChanged = true;
  vtkSmartPointer<vtkCatadioptricCamera> PanelCamera;

  std::string MirrorType;
  std::vector<double> MirrorParameters;
  vtkSmartPointer<vtkCatadioptricCamera> MirrorCamera; // the camera with the mirror replaced
  vtkMTimeType MirrorCameraBase = 0;                   // the base camera's time it was made from
  vtkCatadioptricCamera* MirrorCameraFrom = nullptr;

  vtkSmartPointer<vtkCatadioptricCamera> Camera;
  std::string FileName;
  vtkSmartPointer<vtkCatadioptricCamera> FileCamera;
  std::string LoadedFileName;
};

/**
 * Declares, in the public section of an algorithm's class, the camera members that
 * vtkCatadioptricCameraSlotMacro defines (the one copy of these declarations; VTK's Python and
 * ParaView wrappers expand the macro, so every algorithm that uses it has each member):
 *  - SetCamera / GetCamera: the camera object; takes precedence over the file and the panel.
 *  - SetCalibrationFileName / GetCalibrationFileName: a calibration file (YAML/JSON) used when no
 *    camera object is set (e.g. from ParaView).
 *  - SetMirrorType, SetNumberOfMirrorParameters, SetMirrorParameter and their getters: a mirror in
 *    place of the camera's (ParaView's panel sets these): a type of
 *    vtkCatadioptricCamera::GetMirrorTypes(), or "" (the default; also "from calibration", as
 *    ParaView's panel names it) to keep the camera's own, and
 *    that type's numbers in the order of its keys (Documentation/mirrors.md).
 *  - The panel camera, used when no camera object and no calibration file are set: the built-in
 *    demo camera's values (Data/calibration/demo-camera.yaml) until changed. CameraImageSize in
 *    pixels; FocalLength (fx, fy) and PrincipalPoint (cx, cy) in pixels; Distortion k1, k2, p1,
 *    p2, k3 (OpenCV's order); WorldToCamera, the pose, as 16 numbers row by row or a 4x4 matrix
 *    (from Python, a 4x4 numpy array). A bad value is an error at the next update that names the
 *    property.
 * Use it as `vtkCatadioptricCameraSlotDeclareMacro();`.
 */
#define vtkCatadioptricCameraSlotDeclareMacro()                                                    \
  void SetCamera(vtkCatadioptricCamera* camera);                                                   \
  vtkCatadioptricCamera* GetCamera();                                                              \
  void SetCalibrationFileName(const char* fileName);                                               \
  const char* GetCalibrationFileName();                                                            \
  void SetMirrorType(const char* type);                                                            \
  const char* GetMirrorType();                                                                     \
  void SetNumberOfMirrorParameters(int n);                                                         \
  void SetMirrorParameter(int i, double value);                                                    \
  int GetNumberOfMirrorParameters();                                                               \
  double GetMirrorParameter(int i);                                                                \
  void SetCameraImageSize(int width, int height);                                                  \
  void GetCameraImageSize(int size[2]);                                                            \
  void SetFocalLength(double fx, double fy);                                                       \
  void GetFocalLength(double f[2]);                                                                \
  void SetPrincipalPoint(double cx, double cy);                                                    \
  void GetPrincipalPoint(double c[2]);                                                             \
  void SetDistortion(double k1, double k2, double p1, double p2, double k3);                       \
  void GetDistortion(double coefficients[5]);                                                      \
  void SetWorldToCamera(const double elements[16]);                                                \
  void SetWorldToCamera(const double matrix[4][4]);                                                \
  void GetWorldToCamera(double elements[16])

/**
 * Declares, in the public section, SetTrajectoryFileName and GetTrajectoryFileName
 * (vtkCatadioptricCameraSlotTrajectoryMacro defines them): a trajectory file
 * (Documentation/file-formats.md: TUM or matrix poses) that moves the camera over time: its poses'
 * times are announced as the output's TIME_STEPS (ParaView's animation plays them), and each
 * update takes the pose at the time it asks for. Null or "" (the default): the camera's own pose.
 * Use it as `vtkCatadioptricCameraSlotDeclareTrajectoryMacro();`.
 */
#define vtkCatadioptricCameraSlotDeclareTrajectoryMacro()                                          \
  void SetTrajectoryFileName(const char* fileName);                                                \
  const char* GetTrajectoryFileName()

/**
 * Declares, in the protected section, the slot itself (`CameraSlot`), ResolveCamera(outInfo) (the
 * camera to use for this execution: the object, the file's or the panel's, at the time outInfo
 * asks for) and ResolveValidCamera(outInfo) (the same, and null with an error for a camera that is
 * not valid; defined by vtkCatadioptricCameraSlotValidMacro). Use it as
 * `vtkCatadioptricCameraSlotMembersMacro();`.
 */
#define vtkCatadioptricCameraSlotMembersMacro()                                                    \
  vtkCatadioptricCamera* ResolveCamera(vtkInformation* outInfo = nullptr);                         \
  vtkCatadioptricCamera* ResolveValidCamera(vtkInformation* outInfo = nullptr);                    \
  vtkCatadioptricCameraSlot CameraSlot

/**
 * Defines, in a .cxx, the mirror override of an algorithm that holds a
 * `vtkCatadioptricCameraSlot CameraSlot`: SetMirrorType, SetNumberOfMirrorParameters,
 * SetMirrorParameter and their getters (part of vtkCatadioptricCameraSlotMacro).
 */
#define vtkCatadioptricCameraSlotMirrorMacro(thisClass)                                            \
  void thisClass::SetMirrorType(const char* type)                                                  \
  {                                                                                                \
    if (this->CameraSlot.SetMirrorType(type))                                                      \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  const char* thisClass::GetMirrorType()                                                           \
  {                                                                                                \
    return this->CameraSlot.GetMirrorType();                                                       \
  }                                                                                                \
  void thisClass::SetNumberOfMirrorParameters(int n)                                               \
  {                                                                                                \
    if (this->CameraSlot.SetNumberOfMirrorParameters(n))                                           \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void thisClass::SetMirrorParameter(int i, double value)                                          \
  {                                                                                                \
    if (this->CameraSlot.SetMirrorParameter(i, value))                                             \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  int thisClass::GetNumberOfMirrorParameters()                                                     \
  {                                                                                                \
    return this->CameraSlot.GetNumberOfMirrorParameters();                                         \
  }                                                                                                \
  double thisClass::GetMirrorParameter(int i)                                                      \
  {                                                                                                \
    return this->CameraSlot.GetMirrorParameter(i);                                                 \
  }

/**
 * Defines, in a .cxx, the panel camera of an algorithm that holds a
 * `vtkCatadioptricCameraSlot CameraSlot` (part of vtkCatadioptricCameraSlotMacro):
 * SetCameraImageSize, SetFocalLength, SetPrincipalPoint, SetDistortion, SetWorldToCamera (16
 * numbers or 4x4) and their getters.
 */
#define vtkCatadioptricCameraSlotPanelMacro(thisClass)                                             \
  void thisClass::SetCameraImageSize(int width, int height)                                        \
  {                                                                                                \
    if (this->CameraSlot.SetCameraImageSize(width, height))                                        \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void thisClass::GetCameraImageSize(int size[2])                                                  \
  {                                                                                                \
    this->CameraSlot.GetCameraImageSize(size);                                                     \
  }                                                                                                \
  void thisClass::SetFocalLength(double fx, double fy)                                             \
  {                                                                                                \
    if (this->CameraSlot.SetFocalLength(fx, fy))                                                   \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void thisClass::GetFocalLength(double f[2])                                                      \
  {                                                                                                \
    this->CameraSlot.GetFocalLength(f);                                                            \
  }                                                                                                \
  void thisClass::SetPrincipalPoint(double cx, double cy)                                          \
  {                                                                                                \
    if (this->CameraSlot.SetPrincipalPoint(cx, cy))                                                \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void thisClass::GetPrincipalPoint(double c[2])                                                   \
  {                                                                                                \
    this->CameraSlot.GetPrincipalPoint(c);                                                         \
  }                                                                                                \
  void thisClass::SetDistortion(double k1, double k2, double p1, double p2, double k3)             \
  {                                                                                                \
    const double d[5] = { k1, k2, p1, p2, k3 };                                                    \
    if (this->CameraSlot.SetDistortion(d))                                                         \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void thisClass::GetDistortion(double d[5])                                                       \
  {                                                                                                \
    this->CameraSlot.GetDistortion(d);                                                             \
  }                                                                                                \
  void thisClass::SetWorldToCamera(const double elements[16])                                      \
  {                                                                                                \
    if (this->CameraSlot.SetWorldToCamera(elements))                                               \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void thisClass::SetWorldToCamera(const double matrix[4][4])                                      \
  {                                                                                                \
    this->SetWorldToCamera(&matrix[0][0]);                                                         \
  }                                                                                                \
  void thisClass::GetWorldToCamera(double elements[16])                                            \
  {                                                                                                \
    this->CameraSlot.GetWorldToCamera(elements);                                                   \
  }

/**
 * Defines, in a .cxx, SetTrajectoryFileName and GetTrajectoryFileName of an algorithm that holds
 * a `vtkCatadioptricCameraSlot CameraSlot`.
 */
#define vtkCatadioptricCameraSlotTrajectoryMacro(thisClass)                                        \
  void thisClass::SetTrajectoryFileName(const char* fileName)                                      \
  {                                                                                                \
    if (this->CameraSlot.SetTrajectoryFileName(fileName))                                          \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  const char* thisClass::GetTrajectoryFileName()                                                   \
  {                                                                                                \
    return this->CameraSlot.GetTrajectoryFileName();                                               \
  }

/**
 * Defines, in a .cxx, the camera members of an algorithm that holds a
 * `vtkCatadioptricCameraSlot CameraSlot`: SetCamera, GetCamera, SetCalibrationFileName,
 * GetCalibrationFileName, the mirror override (SetMirrorType, SetNumberOfMirrorParameters,
 * SetMirrorParameter and their getters), the panel camera (vtkCatadioptricCameraSlotPanelMacro),
 * GetMTime (including the camera's) and
 * ResolveCamera(outInfo) (the camera at the time outInfo asks for; reports failures with
 * vtkErrorMacro). Algorithms that follow a trajectory add vtkCatadioptricCameraSlotTrajectoryMacro.
 */
#define vtkCatadioptricCameraSlotMacro(thisClass)                                                  \
  void thisClass::SetCamera(vtkCatadioptricCamera* camera)                                         \
  {                                                                                                \
    if (this->CameraSlot.SetCamera(camera))                                                        \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  vtkCatadioptricCamera* thisClass::GetCamera()                                                    \
  {                                                                                                \
    return this->CameraSlot.GetCamera();                                                           \
  }                                                                                                \
  void thisClass::SetCalibrationFileName(const char* fileName)                                     \
  {                                                                                                \
    if (this->CameraSlot.SetCalibrationFileName(fileName))                                         \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  const char* thisClass::GetCalibrationFileName()                                                  \
  {                                                                                                \
    return this->CameraSlot.GetCalibrationFileName();                                              \
  }                                                                                                \
  vtkMTimeType thisClass::GetMTime()                                                               \
  {                                                                                                \
    const vtkMTimeType own = this->Superclass::GetMTime();                                         \
    const vtkMTimeType camera = this->CameraSlot.GetCameraMTime();                                 \
    return own > camera ? own : camera;                                                            \
  }                                                                                                \
  vtkCatadioptricCameraSlotMirrorMacro(thisClass) vtkCatadioptricCameraSlotPanelMacro(thisClass)   \
    vtkCatadioptricCamera*                                                                         \
    thisClass::ResolveCamera(vtkInformation* outInfo)                                              \
  {                                                                                                \
    std::string error;                                                                             \
    vtkCatadioptricCamera* camera = this->CameraSlot.Resolve(error, outInfo);                      \
    if (!camera)                                                                                   \
    {                                                                                              \
      vtkErrorMacro(<< error);                                                                     \
    }                                                                                              \
    return camera;                                                                                 \
  }

/**
 * Defines ResolveValidCamera(outInfo) for an algorithm with vtkCatadioptricCameraSlotMacro:
 * ResolveCamera(outInfo), and null with an error ("Invalid camera: ...") for a camera that is
 * not valid. What RequestData asks for before projecting.
 */
#define vtkCatadioptricCameraSlotValidMacro(thisClass)                                             \
  vtkCatadioptricCamera* thisClass::ResolveValidCamera(vtkInformation* outInfo)                    \
  {                                                                                                \
    vtkCatadioptricCamera* camera = this->ResolveCamera(outInfo);                                  \
    if (camera && !camera->IsValid())                                                              \
    {                                                                                              \
      vtkErrorMacro("Invalid camera: " << camera->GetLastError());                                 \
      return nullptr;                                                                              \
    }                                                                                              \
    return camera;                                                                                 \
  }

#endif
