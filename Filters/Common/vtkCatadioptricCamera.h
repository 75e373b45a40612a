/**
 * @class   vtkCatadioptricCamera
 * @brief   a non-central catadioptric camera: a perspective camera looking at a curved mirror
 *
 * The camera holds the pinhole intrinsics (focal lengths, principal point, skew, image size),
 * the lens model and its distortion (OpenCV's pinhole or fisheye), the mirror (a type and its
 * parameters, in the camera frame; see GetMirrorTypes()) and the world-to-camera pose. Conventions
 * follow OpenCV: camera frame x right, y down, z forward; pixel (0,0) is the centre of the top-left
 * pixel. Lengths are in any one unit.
 *
 * It loads and saves calibration files (YAML or JSON, see Documentation/opencv-calibration.md),
 * projects world points through the mirror, back-projects pixels to reflected rays, and writes
 * itself to / reads itself from field data, which is how it travels down a pipeline.
 *
 * Every projection returns a status (see StatusCodes) instead of producing NaNs.
 */
#ifndef vtkCatadioptricCamera_h
#define vtkCatadioptricCamera_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for member

#include <string> // for member
#include <vector> // for member

class vtkFieldData;
class vtkInformationIntegerVectorKey;
class vtkDataArray;
class vtkDoubleArray;
class vtkIntArray;
class vtkMatrix4x4;

namespace catar
{
struct CameraModel;
}

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricCamera : public vtkObject
{
public:
  static vtkCatadioptricCamera* New();
  vtkTypeMacro(vtkCatadioptricCamera, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Projection statuses (values of the ProjectionStatus arrays).
  enum StatusCodes
  {
    VALID = 0,            ///< reflection found, pixel inside the image
    OUTSIDE_IMAGE = 1,    ///< reflection found, pixel outside the image
    INSIDE_MIRROR = 2,    ///< the point is inside the mirror's solid
    HIDDEN_BY_MIRROR = 3, ///< the mirror hides the point from all of it the camera sees
    NO_REFLECTION = 4,    ///< grazing, behind the camera, or a pixel whose ray misses the mirror
    INVALID_INPUT = 5     ///< NaN/Inf input or an invalid camera
  };
  /// A short name for a status code ("valid", "inside-mirror", ...).
  static const char* GetStatusName(int status);

  /// Pipeline information key: the camera's image size (width, height), set on its output by
  /// vtkCatadioptricProjection in RequestInformation and passed down by every filter (the key
  /// copies itself downstream), so that an image sink knows its extent before any data exists.
  static vtkInformationIntegerVectorKey* IMAGE_SIZE();

  ///@{
  /// Image size in pixels: at most 32768 a side (clamped) and 2^28 pixels in all (IsValid()).
  vtkSetClampMacro(ImageWidth, int, 1, 32768);
  vtkGetMacro(ImageWidth, int);
  vtkSetClampMacro(ImageHeight, int, 1, 32768);
  vtkGetMacro(ImageHeight, int);
  ///@}

  ///@{
  /// Focal lengths fx, fy in pixels.
  vtkSetVector2Macro(FocalLength, double);
  vtkGetVector2Macro(FocalLength, double);
  ///@}

  ///@{
  /// Principal point cx, cy in pixels (pixel (0,0) is the centre of the top-left pixel).
  vtkSetVector2Macro(PrincipalPoint, double);
  vtkGetVector2Macro(PrincipalPoint, double);
  ///@}

  ///@{
  /// Skew, K(0,1). OpenCV calibrations have 0.
  vtkSetMacro(Skew, double);
  vtkGetMacro(Skew, double);
  ///@}

  ///@{
  /// OpenCV distortion coefficients k1, k2, p1, p2, k3.
  // Written out rather than vtkSetVectorMacro: its unsized `const double data[]` made the Python
  // wrapping read past a scalar argument (SetDistortion(1) crashed).
  void SetDistortion(double k1, double k2, double p1, double p2, double k3);
  void SetDistortion(const double d[5]) { this->SetDistortion(d[0], d[1], d[2], d[3], d[4]); }
  vtkGetVectorMacro(Distortion, double, 5);
  ///@}

  ///@{
  /// The lens model and all its coefficients, as calibration files give them
  /// (Documentation/opencv-calibration.md): "pinhole" with OpenCV's 4, 5, 8, 12 or 14 numbers
  /// (k1 k2 p1 p2 [k3 [k4 k5 k6 [s1 s2 s3 s4 [tauX tauY]]]]), or "fisheye" with k1 k2 k3 k4
  /// (cv::fisheye). SetLens returns false (GetLastError says why; nothing changes) for an unknown
  /// model or a wrong count. SetDistortion sets the first five of a pinhole's.
  bool SetLens(const char* lens, const std::vector<double>& coefficients);
  const char* GetLens();
  std::vector<double> GetDistortionCoefficients();
  ///@}

  ///@{
  /// The mirror's type: one of GetMirrorTypes() (the first is the default). Setting another type
  /// resets the parameters to that type's defaults; an unknown type is an error (vtkErrorMacro,
  /// GetLastError, false) and changes nothing.
  bool SetMirrorType(const char* type);
  const char* GetMirrorType() { return this->MirrorType.c_str(); }
  /// The mirror types there are, and the keys of a type's parameters in order
  /// (Documentation/mirrors.md says what each means).
  static std::vector<std::string> GetMirrorTypes();
  static std::vector<std::string> GetMirrorParameterKeys(const char* type);
  ///@}

  ///@{
  /// One of the mirror's parameters by its key (as in calibration files), camera frame, e.g.
  /// SetMirrorParameter("radius", 0.05). A key the type does not have, or the wrong count of
  /// numbers, is an error (vtkErrorMacro, GetLastError, false) and changes nothing; Get returns an
  /// empty vector for an unknown key.
  bool SetMirrorParameter(const char* key, const std::vector<double>& values);
  bool SetMirrorParameter(const char* key, double value);
  /// A 4x4 key (mirror_to_camera, a quadric's matrix) as a matrix; from Python, a 4x4 numpy array.
  bool SetMirrorParameter(const char* key, const double matrix[4][4]);
  std::vector<double> GetMirrorParameter(const char* key);
  ///@}

  ///@{
  /// All the mirror's numbers, in its type's order (the keys' numbers one after the other).
  /// A wrong count is an error, as above.
  bool SetMirrorParameters(const std::vector<double>& values);
  std::vector<double> GetMirrorParameters() { return this->MirrorParameters; }
  ///@}

  ///@{
  /// World-to-camera pose (p_camera = M p_world). The matrix is copied.
  void SetWorldToCamera(vtkMatrix4x4* matrix);
  vtkMatrix4x4* GetWorldToCamera();
  /// The pose as 16 numbers, row-major (for ParaView and scripts).
  void SetWorldToCameraElements(const double elements[16]);
  /// The pose as a 4x4 matrix (from Python, a 4x4 numpy array or nested lists).
  void SetWorldToCamera(const double matrix[4][4]);
  void GetWorldToCameraElements(double elements[16]);
  /// Camera centre in world coordinates.
  void GetCameraPosition(double position[3]);
  ///@}

  /// True when the parameters describe a usable camera; otherwise GetLastError() says why.
  bool IsValid();

  /// The last problem met by IsValid, Load or Save ("" if none).
  const char* GetLastError() { return this->LastError.c_str(); }

  ///@{
  /// Read / write a calibration file (YAML or JSON by extension). Return false on failure and
  /// report it through vtkErrorMacro and GetLastError(); a failed Load leaves the camera as it was.
  bool Load(const char* fileName);
  bool Save(const char* fileName);
  ///@}

  ///@{
  /// Forward projection of a world point. Returns a status code; pixel and mirrorPoint (camera
  /// frame) are set for VALID and OUTSIDE_IMAGE and zero otherwise. solver: 0 quartic, 1
  /// iterative, 2 automatic (the default: the faster where exact, catar::SolverType::Automatic).
  int ProjectWorldPoint(const double point[3], double pixel[2], double mirrorPoint[3]);
  int ProjectWorldPoint(const double point[3], double pixel[2], double mirrorPoint[3], int solver);
  ///@}

  /// Back projection of a pixel to the reflected ray in world coordinates: it leaves `origin`
  /// (on the mirror) along the unit vector `direction`. Returns a status code.
  int BackProjectPixel(const double pixel[2], double origin[3], double direction[3]);

  ///@{
  /// The same for many points at once, on the thread pool (vtkCatadioptricParallel): the results
  /// are those of ProjectWorldPoint / BackProjectPixel point by point. ProjectWorldPoints takes
  /// world points (3 components, any numeric type) and fills pixels (2 components), statuses and
  /// mirror points (3 components, camera frame); BackProjectPixels takes pixels (2 components)
  /// and fills ray origins and unit directions (3 components, world frame) and statuses. The
  /// output arrays are resized to the input's tuples. False, after reporting it through
  /// vtkErrorMacro and GetLastError(), for a missing array, a wrong component count or an
  /// invalid camera. From Python, catadioptricar.project_points and back_project wrap them for
  /// numpy arrays.
  bool ProjectWorldPoints(vtkDataArray* points, vtkDoubleArray* pixels, vtkIntArray* statuses,
    vtkDoubleArray* mirrorPoints, int solver = 2);
  bool BackProjectPixels(vtkDataArray* pixels, vtkDoubleArray* origins, vtkDoubleArray* directions,
    vtkIntArray* statuses);
  ///@}

  ///@{
  /// Store the camera in / restore it from field data (arrays CameraIntrinsics,
  /// CameraDistortion (14 numbers; 5 are read too), CameraLens (a string; pinhole when absent),
  /// MirrorType (a string), MirrorParameters, WorldToCamera). ReadFromFieldData
  /// returns false if any is missing or malformed.
  void WriteToFieldData(vtkFieldData* fieldData);
  bool ReadFromFieldData(vtkFieldData* fieldData);
  ///@}

  /// Copies all parameters from another camera.
  void DeepCopy(vtkCatadioptricCamera* other);

  /// The modification time includes the pose matrix.
  vtkMTimeType GetMTime() override;

#ifndef __VTK_WRAP__
  ///@{
  /// The model as the Core library sees it (C++ only).
  catar::CameraModel GetModel();
  void SetModel(const catar::CameraModel& model);
  ///@}
#endif

protected:
  vtkCatadioptricCamera();
  ~vtkCatadioptricCamera() override;

  int ImageWidth = 1328;
  int ImageHeight = 1048;
  double FocalLength[2] = { 1000.0, 1000.0 };
  double PrincipalPoint[2] = { 663.5, 523.5 };
  double Skew = 0.0;
  int Lens = 0;                         // catar::LensType
  double Distortion[14] = {};           // OpenCV's order (catar::Distortion)
  std::string MirrorType;               // set by the constructor: the demo rig's mirror
  std::vector<double> MirrorParameters; // its numbers
  vtkSmartPointer<vtkMatrix4x4> WorldToCamera;
  std::string LastError;

private:
  vtkCatadioptricCamera(const vtkCatadioptricCamera&) = delete;
  void operator=(const vtkCatadioptricCamera&) = delete;
};

#endif
