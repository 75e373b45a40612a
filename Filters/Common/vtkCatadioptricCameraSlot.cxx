#include "vtkCatadioptricCameraSlot.h"

#include "CalibrationIO.h"
#include "CameraModel.h"

#include "vtkCatadioptricCamera.h"

vtkCatadioptricCameraSlot::vtkCatadioptricCameraSlot() = default;
vtkCatadioptricCameraSlot::~vtkCatadioptricCameraSlot() = default;

bool vtkCatadioptricCameraSlot::SetCamera(vtkCatadioptricCamera* camera)
{
  if (this->Camera == camera)
  {
    return false;
  }
  this->Camera = camera;
  return true;
}

vtkCatadioptricCamera* vtkCatadioptricCameraSlot::GetCamera() const
{
  return this->Camera;
}

bool vtkCatadioptricCameraSlot::SetCalibrationFileName(const char* fileName)
{
  const std::string name = fileName ? fileName : "";
  if (name == this->FileName)
  {
    return false;
  }
  this->FileName = name;
  return true;
}

const char* vtkCatadioptricCameraSlot::GetCalibrationFileName() const
{
  return this->FileName.empty() ? nullptr : this->FileName.c_str();
}

vtkMTimeType vtkCatadioptricCameraSlot::GetCameraMTime() const
{
  return this->Camera ? this->Camera->GetMTime() : 0;
}

vtkCatadioptricCamera* vtkCatadioptricCameraSlot::Resolve(std::string& error)
{
  if (this->Camera)
  {
    return this->Camera;
  }
  if (this->FileName.empty())
  {
    error = "No camera: call SetCamera() or set CalibrationFileName.";
    return nullptr;
  }
  if (!this->FileCamera || this->LoadedFileName != this->FileName)
  {
    catar::CameraModel model;
    std::string why;
    if (!catar::LoadCalibration(this->FileName, model, why))
    {
      error = "Cannot load the calibration: " + why;
      return nullptr;
    }
    this->FileCamera = vtkSmartPointer<vtkCatadioptricCamera>::New();
    this->FileCamera->SetModel(model);
    this->LoadedFileName = this->FileName;
  }
  return this->FileCamera;
}
