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
#include <sstream>

namespace
{
template<std::size_t N>
bool Assign(double (&to)[N], const double* from)
{
  if (std::equal(to, to + N, from))
  {
    return false;
  }
  std::copy(from, from + N, to);
  return true;
}
}

vtkCatadioptricCameraSlot::vtkCatadioptricCameraSlot()
{
  const catar::CameraModel& demo = catar::DemoCamera(); // the panel starts as the demo camera
  this->PanelImageSize[0] = demo.intrinsics.width;
  this->PanelImageSize[1] = demo.intrinsics.height;
  this->PanelFocalLength[0] = demo.intrinsics.fx;
  this->PanelFocalLength[1] = demo.intrinsics.fy;
  this->PanelPrincipalPoint[0] = demo.intrinsics.cx;
  this->PanelPrincipalPoint[1] = demo.intrinsics.cy;
  const catar::Distortion& d = demo.distortion;
  const double distortion[5] = { d.k1, d.k2, d.p1, d.p2, d.k3 };
  std::copy(distortion, distortion + 5, this->PanelDistortion);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      this->PanelWorldToCamera[4 * r + c] = demo.worldToCamera(r, c);
    }
  }
}

vtkCatadioptricCameraSlot::~vtkCatadioptricCameraSlot() = default;

bool vtkCatadioptricCameraSlot::SetCameraImageSize(int width, int height)
{
  if (this->PanelImageSize[0] == width && this->PanelImageSize[1] == height)
  {
    return false;
  }
  this->PanelImageSize[0] = width;
  this->PanelImageSize[1] = height;
  this->PanelChanged = true;
  return true;
}

bool vtkCatadioptricCameraSlot::SetFocalLength(double fx, double fy)
{
  const double f[2] = { fx, fy };
  const bool changed = Assign(this->PanelFocalLength, f);
  this->PanelChanged = this->PanelChanged || changed;
  return changed;
}

bool vtkCatadioptricCameraSlot::SetPrincipalPoint(double cx, double cy)
{
  const double c[2] = { cx, cy };
  const bool changed = Assign(this->PanelPrincipalPoint, c);
  this->PanelChanged = this->PanelChanged || changed;
  return changed;
}

bool vtkCatadioptricCameraSlot::SetDistortion(const double coefficients[5])
{
  const bool changed = Assign(this->PanelDistortion, coefficients);
  this->PanelChanged = this->PanelChanged || changed;
  return changed;
}

bool vtkCatadioptricCameraSlot::SetWorldToCamera(const double elements[16])
{
  const bool changed = Assign(this->PanelWorldToCamera, elements);
  this->PanelChanged = this->PanelChanged || changed;
  return changed;
}

void vtkCatadioptricCameraSlot::GetCameraImageSize(int size[2]) const
{
  std::copy(this->PanelImageSize, this->PanelImageSize + 2, size);
}

void vtkCatadioptricCameraSlot::GetFocalLength(double f[2]) const
{
  std::copy(this->PanelFocalLength, this->PanelFocalLength + 2, f);
}

void vtkCatadioptricCameraSlot::GetPrincipalPoint(double c[2]) const
{
  std::copy(this->PanelPrincipalPoint, this->PanelPrincipalPoint + 2, c);
}

void vtkCatadioptricCameraSlot::GetDistortion(double coefficients[5]) const
{
  std::copy(this->PanelDistortion, this->PanelDistortion + 5, coefficients);
}

void vtkCatadioptricCameraSlot::GetWorldToCamera(double elements[16]) const
{
  std::copy(this->PanelWorldToCamera, this->PanelWorldToCamera + 16, elements);
}

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
  // ParaView's panel names the default "from calibration" (a blank entry looked unset).
  std::string name = type ? type : "";
  if (name == kMirrorFromCalibration)
  {
    name.clear();
  }
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
      error = "Mirror Type '" + this->MirrorType + "' with Mirror Parameters: " + problem;
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
    return this->ResolvePanel(error);
  }
  if (!this->FileCamera || this->LoadedFileName != this->FileName)
  {
    catar::CameraModel model;
    std::string why;
    if (!catar::LoadCalibration(this->FileName, model, why))
    {
      error = "Calibration File Name: cannot load the calibration: " + why;
      return nullptr;
    }
    this->FileCamera = vtkSmartPointer<vtkCatadioptricCamera>::New();
    this->FileCamera->SetModel(model);
    this->LoadedFileName = this->FileName;
  }
  return this->FileCamera;
}

vtkCatadioptricCamera* vtkCatadioptricCameraSlot::ResolvePanel(std::string& error)
{
  if (this->PanelCamera && !this->PanelChanged)
  {
    return this->PanelCamera;
  }
  // Each value is checked here so that the error names the panel property to change.
  std::ostringstream why;
  const auto finite = [](const double* v, int n) {
    return std::all_of(v, v + n, [](double x) { return std::isfinite(x); });
  };
  const int* size = this->PanelImageSize;
  if (size[0] <= 0 || size[1] <= 0 || size[0] > catar::kMaxImageSide ||
    size[1] > catar::kMaxImageSide ||
    static_cast<long long>(size[0]) * size[1] > catar::kMaxImagePixels)
  {
    why << "Camera Image Size must be positive and at most " << catar::kMaxImageSide
        << " pixels a side and " << catar::kMaxImagePixels << " pixels in all (it is " << size[0]
        << " x " << size[1] << ").";
  }
  else if (!finite(this->PanelFocalLength, 2) ||
    !(this->PanelFocalLength[0] > 0.0 && this->PanelFocalLength[1] > 0.0))
  {
    why << "Focal Length must be two positive numbers of pixels (it is "
        << this->PanelFocalLength[0] << ", " << this->PanelFocalLength[1] << ").";
  }
  else if (!finite(this->PanelPrincipalPoint, 2))
  {
    why << "Principal Point must be finite.";
  }
  else if (!finite(this->PanelDistortion, 5))
  {
    why << "Distortion must be finite.";
  }
  if (!why.str().empty())
  {
    error = why.str();
    return nullptr;
  }
  catar::CameraModel model = catar::DemoCamera();
  model.intrinsics.width = size[0];
  model.intrinsics.height = size[1];
  model.intrinsics.fx = this->PanelFocalLength[0];
  model.intrinsics.fy = this->PanelFocalLength[1];
  model.intrinsics.cx = this->PanelPrincipalPoint[0];
  model.intrinsics.cy = this->PanelPrincipalPoint[1];
  model.intrinsics.skew = 0.0;
  const double* d = this->PanelDistortion;
  model.distortion = catar::Distortion{ d[0], d[1], d[2], d[3], d[4] };
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      model.worldToCamera(r, c) = this->PanelWorldToCamera[4 * r + c];
    }
  }
  const std::string problem = model.Validate();
  if (!problem.empty())
  {
    // What is left for Validate is the pose (the mirror is the demo's until Mirror Type is set).
    error = "World To Camera: " + problem + " (a rigid transform, 16 numbers row by row).";
    return nullptr;
  }
  if (!this->PanelCamera)
  {
    this->PanelCamera = vtkSmartPointer<vtkCatadioptricCamera>::New();
  }
  this->PanelCamera->SetModel(model);
  this->PanelChanged = false;
  return this->PanelCamera;
}
