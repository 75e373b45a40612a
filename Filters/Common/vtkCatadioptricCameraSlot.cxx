#include "vtkCatadioptricCameraSlot.h"

#include "CalibrationIO.h"
#include "CameraModel.h"
#include "Mirror.h"
#include "Trajectory.h"

#include "vtkCatadioptricCamera.h"
#include "vtkInformation.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>

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

bool vtkCatadioptricCameraSlot::SetMirrorType(const char* type)
{
  const std::string name = type ? type : "";
  if (name == this->MirrorType)
  {
    return false;
  }
  this->MirrorType = name;
  return true;
}

bool vtkCatadioptricCameraSlot::SetNumberOfMirrorParameters(int n)
{
  // At most the largest type's count (the quadric's 34) and a little more: the rest is an error
  // at Resolve, not an allocation.
  n = std::max(0, std::min(n, 64));
  if (n == static_cast<int>(this->MirrorParameters.size()))
  {
    return false;
  }
  this->MirrorParameters.resize(static_cast<std::size_t>(n), 0.0);
  return true;
}

bool vtkCatadioptricCameraSlot::SetMirrorParameter(int i, double value)
{
  if (i < 0 || i >= static_cast<int>(this->MirrorParameters.size()) ||
    this->MirrorParameters[i] == value)
  {
    return false;
  }
  this->MirrorParameters[i] = value;
  return true;
}

double vtkCatadioptricCameraSlot::GetMirrorParameter(int i) const
{
  return i >= 0 && i < static_cast<int>(this->MirrorParameters.size()) ? this->MirrorParameters[i]
                                                                       : 0.0;
}

bool vtkCatadioptricCameraSlot::SetTrajectoryFileName(const char* fileName)
{
  const std::string name = fileName ? fileName : "";
  if (name == this->TrajectoryName)
  {
    return false;
  }
  this->TrajectoryName = name;
  return true;
}

const char* vtkCatadioptricCameraSlot::GetTrajectoryFileName() const
{
  return this->TrajectoryName.empty() ? nullptr : this->TrajectoryName.c_str();
}

const catar::Trajectory* vtkCatadioptricCameraSlot::LoadTrajectory(std::string& error)
{
  if (this->TrajectoryName.empty())
  {
    return nullptr;
  }
  if (!this->LoadedTrajectory || this->LoadedTrajectoryName != this->TrajectoryName)
  {
    auto trajectory = std::make_shared<catar::Trajectory>();
    if (!catar::LoadTrajectory(this->TrajectoryName, *trajectory, error))
    {
      error = "TrajectoryFileName: " + error;
      this->LoadedTrajectory = nullptr;
      return nullptr;
    }
    this->LoadedTrajectory = trajectory;
    this->LoadedTrajectoryName = this->TrajectoryName;
  }
  return this->LoadedTrajectory.get();
}

bool vtkCatadioptricCameraSlot::AnnounceTimeSteps(vtkInformation* outInfo, std::string& error)
{
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (this->TrajectoryName.empty())
  {
    return true;
  }
  const catar::Trajectory* trajectory = this->LoadTrajectory(error);
  if (!trajectory)
  {
    return false;
  }
  std::vector<double> times;
  times.reserve(trajectory->poses.size());
  for (const catar::TimedPose& p : trajectory->poses)
  {
    times.push_back(p.time);
  }
  outInfo->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
  const double range[2] = { times.front(), times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return true;
}

vtkCatadioptricCamera* vtkCatadioptricCameraSlot::Resolve(
  std::string& error, vtkInformation* outInfo)
{
  vtkCatadioptricCamera* camera = this->ResolveMirror(error);
  if (!camera || this->TrajectoryName.empty())
  {
    return camera;
  }
  const catar::Trajectory* trajectory = this->LoadTrajectory(error);
  if (!trajectory)
  {
    return nullptr;
  }
  double time = trajectory->poses.front().time;
  if (outInfo && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    time = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  }
  // The camera at that time's pose, remade only when the camera or the time changed.
  if (!this->TimedCamera || this->TimedCameraFrom != camera ||
    this->TimedCameraBase != camera->GetMTime() || !(this->TimedCameraTime == time))
  {
    catar::CameraModel model = camera->GetModel();
    model.worldToCamera = trajectory->PoseAt(time);
    if (!this->TimedCamera)
    {
      this->TimedCamera = vtkSmartPointer<vtkCatadioptricCamera>::New();
    }
    this->TimedCamera->SetModel(model);
    this->TimedCameraFrom = camera;
    this->TimedCameraBase = camera->GetMTime();
    this->TimedCameraTime = time;
  }
  return this->TimedCamera;
}

vtkCatadioptricCamera* vtkCatadioptricCameraSlot::ResolveMirror(std::string& error)
{
  vtkCatadioptricCamera* base = this->ResolveBase(error);
  if (!base || this->MirrorType.empty())
  {
    return base;
  }
  // The base camera with the mirror replaced, remade only when either changed.
  const catar::MirrorDescription mirror(this->MirrorType, this->MirrorParameters);
  if (!this->MirrorCamera || this->MirrorCameraFrom != base ||
    this->MirrorCameraBase != base->GetMTime() || this->MirrorCamera->GetModel().mirror != mirror)
  {
    catar::CameraModel model = base->GetModel();
    model.mirror = mirror;
    const std::string problem = catar::ValidateMirror(model.mirror);
    if (!problem.empty())
    {
      error = "MirrorType '" + this->MirrorType + "' with MirrorParameters: " + problem;
      return nullptr;
    }
    if (!this->MirrorCamera)
    {
      this->MirrorCamera = vtkSmartPointer<vtkCatadioptricCamera>::New();
    }
    this->MirrorCamera->SetModel(model);
    this->MirrorCameraFrom = base;
    this->MirrorCameraBase = base->GetMTime();
  }
  return this->MirrorCamera;
}

vtkCatadioptricCamera* vtkCatadioptricCameraSlot::ResolveBase(std::string& error)
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
