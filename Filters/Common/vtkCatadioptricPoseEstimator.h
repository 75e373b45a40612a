/**
 * @class   vtkCatadioptricPoseEstimator
 * @brief   the camera's pose from pixels of known world points (generalized absolute pose)
 *
 * VTK's face of catar::EstimatePose (Module/Vision/PoseEstimation.h;
 * Documentation/pose-from-the-image.md): given a camera (intrinsics, distortion, mirror) and, for N
 * known world points, the pixels where the image shows them, finds the world-to-camera pose. Each
 * pixel's reflected ray must pass through its point: OpenGV's GP3P in RANSAC, inliers by the pixel
 * reprojection error through the mirror, then a Ceres refinement. Outliers are rejected.
 *
 * @code
 * estimator.SetCamera(camera)
 * estimator.SetObservations(points, pixels)   # vtkPoints (N), vtkDataArray (N x 2)
 * if estimator.Estimate():
 *     camera.SetWorldToCamera(estimator.GetWorldToCamera())
 * @endcode
 */
#ifndef vtkCatadioptricPoseEstimator_h
#define vtkCatadioptricPoseEstimator_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "vtkNew.h"                     // for members
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <string> // for members

class vtkCatadioptricCamera;
class vtkDataArray;
class vtkMatrix4x4;
class vtkPoints;
class vtkUnsignedCharArray;

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricPoseEstimator : public vtkObject
{
public:
  static vtkCatadioptricPoseEstimator* New();
  vtkTypeMacro(vtkCatadioptricPoseEstimator, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera: intrinsics, distortion and mirror (its pose is not used).
  void SetCamera(vtkCatadioptricCamera* camera);
  vtkCatadioptricCamera* GetCamera();
  ///@}

  /// The observations: world points and the pixels (N x 2, OpenCV's convention: (0, 0) the centre
  /// of the top-left pixel) where the image shows them. Copied.
  void SetObservations(vtkPoints* world, vtkDataArray* pixels);

  ///@{
  /// RANSAC: the reprojection error (pixels) under which an observation is an inlier (default 2),
  /// the most iterations (default 1000) and the seed (the result is the same for a seed).
  vtkSetClampMacro(InlierThreshold, double, 1e-6, 1e6);
  vtkGetMacro(InlierThreshold, double);
  vtkSetClampMacro(MaximumIterations, int, 1, 1000000);
  vtkGetMacro(MaximumIterations, int);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  /// Estimates the pose. False with a sentence in GetLastError() (too few points, collinear
  /// points, nearly parallel rays, non-finite input, no pose found, a bad camera).
  bool Estimate();

  /// The last estimate: the world-to-camera pose, the inliers (1 per observation that is one),
  /// their number and the RMS reprojection error over them (pixels).
  vtkMatrix4x4* GetWorldToCamera();
  vtkUnsignedCharArray* GetInliers();
  vtkGetMacro(NumberOfInliers, int);
  vtkGetMacro(RMSError, double);

  /// The last error ("" if none).
  const char* GetLastError();

protected:
  vtkCatadioptricPoseEstimator();
  ~vtkCatadioptricPoseEstimator() override;

  double InlierThreshold = 2.0;
  int MaximumIterations = 1000;
  unsigned int Seed = 0;
  int NumberOfInliers = 0;
  double RMSError = 0.0;

private:
  vtkCatadioptricPoseEstimator(const vtkCatadioptricPoseEstimator&) = delete;
  void operator=(const vtkCatadioptricPoseEstimator&) = delete;

  vtkSmartPointer<vtkCatadioptricCamera> Camera;
  vtkNew<vtkPoints> World;
  vtkNew<vtkPoints> Pixels; // z = 0
  vtkNew<vtkMatrix4x4> WorldToCamera;
  vtkNew<vtkUnsignedCharArray> Inliers;
  std::string Error;
};

#endif
