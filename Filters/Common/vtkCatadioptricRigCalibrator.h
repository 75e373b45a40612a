/**
 * @class   vtkCatadioptricRigCalibrator
 * @brief   the rig's mirror (and lens) from images of a marker board seen in the mirror
 *
 * VTK's face of catar::CalibrateRigFromImages (Module/Vision/RigCalibration.h;
 * Documentation/calibrate-your-rig.md), what catadioptric-calibrate runs: given a starting camera
 * (its lens, and the mirror's type and a guess), a marker board file and several images of the
 * board in the mirror, estimates the mirror (and with FreeLens the focal lengths, principal point
 * and distortion) and every view's board pose through the exact projection.
 *
 * @code
 * calibrator.SetCamera(start)                # a vtkCatadioptricCamera
 * calibrator.SetBoardFileName("board.yaml")
 * for name in files: calibrator.AddImageFile(name)
 * if calibrator.Calibrate():
 *     rig = calibrator.GetCalibratedCamera()  # a new vtkCatadioptricCamera
 *     calibrator.Save("rig.yaml")            # with the calibration map
 * @endcode
 */
#ifndef vtkCatadioptricRigCalibrator_h
#define vtkCatadioptricRigCalibrator_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <memory> // for members
#include <string> // for members
#include <vector> // for members

class vtkCatadioptricCamera;
class vtkImageData;

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricRigCalibrator : public vtkObject
{
public:
  static vtkCatadioptricRigCalibrator* New();
  vtkTypeMacro(vtkCatadioptricRigCalibrator, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The starting camera: its lens, and its mirror's type and starting guess.
  void SetCamera(vtkCatadioptricCamera* camera);
  vtkCatadioptricCamera* GetCamera();
  ///@}

  ///@{
  /// The marker board file (Documentation/markers.md).
  vtkSetStdStringFromCharMacro(BoardFileName);
  vtkGetCharFromStdStringMacro(BoardFileName);
  ///@}

  /// Adds the frames of an image file, a numbered image pattern or a video (every frame). False
  /// with a sentence in GetLastError() when it cannot be read.
  bool AddImageFile(const char* fileName);
  /// Adds an image (unsigned char, 3 or 4 components; VTK's bottom row first), copied. False with a
  /// sentence when it is not one.
  bool AddImage(vtkImageData* image);
  /// Forgets the images added.
  void RemoveAllImages();
  int GetNumberOfImages();

  ///@{
  /// Also refine the lens's focal lengths, principal point and distortion (default off).
  vtkSetMacro(FreeLens, bool);
  vtkGetMacro(FreeLens, bool);
  vtkBooleanMacro(FreeLens, bool);
  ///@}

  ///@{
  /// A calibration whose corners' RMS exceeds this (pixels) is refused (default 2).
  vtkSetClampMacro(MaximumRMSError, double, 1e-3, 1e3);
  vtkGetMacro(MaximumRMSError, double);
  ///@}

  /// Calibrates. False with a sentence in GetLastError() (no camera or board, too few views, a
  /// board that does not fit, numbers the views do not fix, ...).
  bool Calibrate();

  /// The last calibration: a new camera with the calibrated lens and mirror (the starting
  /// camera's pose), the corners' RMS (pixels), the images used, and each estimated number's name
  /// (as RigCalibration.h names them: "center_x", "radius", "tilt_x", "a", "fx", "k1", ...), value,
  /// standard deviation and unit; the views left out, each with why.
  vtkCatadioptricCamera* GetCalibratedCamera();
  vtkGetMacro(RMSError, double);
  vtkGetMacro(NumberOfImagesUsed, int);
  std::vector<std::string> GetEstimatedNames();
  std::vector<double> GetEstimatedValues();
  std::vector<double> GetEstimatedSigmas();
  std::vector<std::string> GetEstimatedUnits();
  std::vector<std::string> GetLeftOut();

  /// Writes the calibrated camera with its `calibration` map (as catadioptric-calibrate -o).
  bool Save(const char* fileName);

  /// The last error ("" if none).
  const char* GetLastError();

protected:
  vtkCatadioptricRigCalibrator();
  ~vtkCatadioptricRigCalibrator() override;

private:
  vtkCatadioptricRigCalibrator(const vtkCatadioptricRigCalibrator&) = delete;
  void operator=(const vtkCatadioptricRigCalibrator&) = delete;

  bool Fail(const std::string& error);

  vtkSmartPointer<vtkCatadioptricCamera> Camera;
  vtkSmartPointer<vtkCatadioptricCamera> Calibrated;
  std::string BoardFileName;
  bool FreeLens = false;
  double MaximumRMSError = 2.0;
  double RMSError = 0.0;
  int NumberOfImagesUsed = 0;
  std::string Error;
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
