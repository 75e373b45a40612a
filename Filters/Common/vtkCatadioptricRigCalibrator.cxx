#include "vtkCatadioptricRigCalibrator.h"

#include "CalibrationIO.h"
#include "Markers.h"
#include "RigCalibration.h"
#include "VideoIO.h"

#include "vtkCatadioptricCamera.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

vtkStandardNewMacro(vtkCatadioptricRigCalibrator);

struct vtkCatadioptricRigCalibrator::Internals
{
  std::vector<catar::Frame> Frames;
  std::vector<std::string> Names;
  catar::CalibrationResult Result;
  catar::CalibrationRecord Record;
};

vtkCatadioptricRigCalibrator::vtkCatadioptricRigCalibrator()
  : Internal(new Internals)
{
}

vtkCatadioptricRigCalibrator::~vtkCatadioptricRigCalibrator() = default;

bool vtkCatadioptricRigCalibrator::Fail(const std::string& error)
{
  this->Error = error;
  vtkErrorMacro(<< this->Error);
  return false;
}

void vtkCatadioptricRigCalibrator::SetCamera(vtkCatadioptricCamera* camera)
{
  if (this->Camera != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}

vtkCatadioptricCamera* vtkCatadioptricRigCalibrator::GetCamera()
{
  return this->Camera;
}

bool vtkCatadioptricRigCalibrator::AddImageFile(const char* fileName)
{
  if (!fileName || !*fileName)
  {
    return this->Fail("AddImageFile: give a file name");
  }
  catar::FrameReader reader;
  std::string error;
  if (!reader.Open(fileName, error))
  {
    return this->Fail(std::string(fileName) + ": " + error);
  }
  const long long count = reader.GetNumberOfFrames();
  for (long long k = 0; k < count; ++k)
  {
    catar::Frame frame;
    if (!reader.Read(k, frame, error))
    {
      return this->Fail(std::string(fileName) + ": " + error);
    }
    this->Internal->Frames.push_back(std::move(frame));
    this->Internal->Names.push_back(
      count > 1 ? std::string(fileName) + "#" + std::to_string(k) : std::string(fileName));
  }
  this->Modified();
  return true;
}

bool vtkCatadioptricRigCalibrator::AddImage(vtkImageData* image)
{
  vtkUnsignedCharArray* scalars =
    image ? vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars()) : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  const int components = scalars ? scalars->GetNumberOfComponents() : 0;
  if (!scalars || (components != 3 && components != 4) || dims[2] != 1 || dims[0] < 1 ||
    dims[1] < 1)
  {
    return this->Fail("AddImage: give a 2D image of unsigned char RGB or RGBA scalars");
  }
  catar::Frame frame;
  frame.width = dims[0];
  frame.height = dims[1];
  frame.rgba.resize(static_cast<std::size_t>(dims[0]) * dims[1] * 4);
  const unsigned char* in = scalars->GetPointer(0);
  for (int y = 0; y < dims[1]; ++y)
  {
    // VTK's rows run bottom to top; the frame's top to bottom.
    const unsigned char* row =
      in + static_cast<std::size_t>(dims[1] - 1 - y) * dims[0] * components;
    unsigned char* out = frame.rgba.data() + static_cast<std::size_t>(y) * dims[0] * 4;
    for (int x = 0; x < dims[0]; ++x)
    {
      out[4 * x] = row[components * x];
      out[4 * x + 1] = row[components * x + 1];
      out[4 * x + 2] = row[components * x + 2];
      out[4 * x + 3] = components == 4 ? row[components * x + 3] : 255;
    }
  }
  this->Internal->Names.push_back("image " + std::to_string(this->Internal->Frames.size() + 1));
  this->Internal->Frames.push_back(std::move(frame));
  this->Modified();
  return true;
}

void vtkCatadioptricRigCalibrator::RemoveAllImages()
{
  this->Internal->Frames.clear();
  this->Internal->Names.clear();
  this->Modified();
}

int vtkCatadioptricRigCalibrator::GetNumberOfImages()
{
  return static_cast<int>(this->Internal->Frames.size());
}

bool vtkCatadioptricRigCalibrator::Calibrate()
{
  this->Calibrated = nullptr;
  this->RMSError = 0.0;
  this->NumberOfImagesUsed = 0;
  this->Internal->Result = catar::CalibrationResult();
  this->Internal->Record = catar::CalibrationRecord();
  if (!this->Camera)
  {
    return this->Fail("No camera: call SetCamera() with the starting camera");
  }
  catar::MarkerBoard board;
  std::string error;
  if (this->BoardFileName.empty())
  {
    return this->Fail("No board: call SetBoardFileName()");
  }
  if (!catar::LoadMarkerBoard(this->BoardFileName, board, error))
  {
    return this->Fail(error);
  }
  std::vector<catar::CalibrationImage> images;
  for (std::size_t i = 0; i < this->Internal->Frames.size(); ++i)
  {
    const catar::Frame& f = this->Internal->Frames[i];
    images.push_back({ this->Internal->Names[i], f.width, f.height, f.rgba.data() });
  }
  catar::CalibrationOptions options;
  options.freeLens = this->FreeLens;
  options.maxRmsPixels = this->MaximumRMSError;
  const catar::CameraModel start = this->Camera->GetModel();
  catar::CalibrationResult r = catar::CalibrateRigFromImages(start, board, images, options);
  if (!r.ok)
  {
    return this->Fail(r.error);
  }
  this->Error.clear();
  catar::CameraModel model = r.camera;
  model.worldToCamera = start.worldToCamera;
  this->Calibrated = vtkSmartPointer<vtkCatadioptricCamera>::New();
  this->Calibrated->SetModel(model);
  this->RMSError = r.rmsPixels;
  this->NumberOfImagesUsed = r.imagesUsed;
  this->Internal->Record = catar::RecordOf(r, this->Internal->Names);
  this->Internal->Result = std::move(r);
  this->Modified();
  return true;
}

vtkCatadioptricCamera* vtkCatadioptricRigCalibrator::GetCalibratedCamera()
{
  return this->Calibrated;
}

std::vector<std::string> vtkCatadioptricRigCalibrator::GetEstimatedNames()
{
  std::vector<std::string> out;
  for (const auto& n : this->Internal->Record.estimated)
  {
    out.push_back(n.name);
  }
  return out;
}

std::vector<double> vtkCatadioptricRigCalibrator::GetEstimatedValues()
{
  std::vector<double> out;
  for (const auto& n : this->Internal->Record.estimated)
  {
    out.push_back(n.value);
  }
  return out;
}

std::vector<double> vtkCatadioptricRigCalibrator::GetEstimatedSigmas()
{
  std::vector<double> out;
  for (const auto& n : this->Internal->Record.estimated)
  {
    out.push_back(n.sigma);
  }
  return out;
}

std::vector<std::string> vtkCatadioptricRigCalibrator::GetEstimatedUnits()
{
  std::vector<std::string> out;
  for (const auto& n : this->Internal->Record.estimated)
  {
    out.push_back(n.unit);
  }
  return out;
}

std::vector<std::string> vtkCatadioptricRigCalibrator::GetLeftOut()
{
  return this->Internal->Result.skipped;
}

bool vtkCatadioptricRigCalibrator::Save(const char* fileName)
{
  if (!this->Calibrated)
  {
    return this->Fail("Save: nothing calibrated (call Calibrate() first)");
  }
  std::string error;
  if (!fileName ||
    !catar::SaveCalibration(fileName, this->Calibrated->GetModel(), error, &this->Internal->Record))
  {
    return this->Fail(fileName ? error : "Save: give a file name");
  }
  return true;
}

const char* vtkCatadioptricRigCalibrator::GetLastError()
{
  return this->Error.c_str();
}

void vtkCatadioptricRigCalibrator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BoardFileName: " << this->BoardFileName << "\n";
  os << indent << "Images: " << this->Internal->Frames.size() << "\n";
  os << indent << "FreeLens: " << this->FreeLens << "\n";
  os << indent << "MaximumRMSError: " << this->MaximumRMSError << "\n";
  os << indent << "RMSError: " << this->RMSError << "\n";
  os << indent << "NumberOfImagesUsed: " << this->NumberOfImagesUsed << "\n";
}
