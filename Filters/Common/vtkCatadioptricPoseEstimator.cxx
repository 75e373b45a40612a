#include "vtkCatadioptricPoseEstimator.h"

#include "PoseEstimation.h"

#include "vtkCatadioptricCamera.h"
#include "vtkDataArray.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

vtkStandardNewMacro(vtkCatadioptricPoseEstimator);

vtkCatadioptricPoseEstimator::vtkCatadioptricPoseEstimator()
{
  this->Inliers->SetName("Inliers");
}

vtkCatadioptricPoseEstimator::~vtkCatadioptricPoseEstimator() = default;

void vtkCatadioptricPoseEstimator::SetCamera(vtkCatadioptricCamera* camera)
{
  if (this->Camera != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}

vtkCatadioptricCamera* vtkCatadioptricPoseEstimator::GetCamera()
{
  return this->Camera;
}

void vtkCatadioptricPoseEstimator::SetObservations(vtkPoints* world, vtkDataArray* pixels)
{
  this->World->Initialize();
  this->Pixels->Initialize();
  this->Error.clear();
  if (!world || !pixels)
  {
    this->Error = "SetObservations: give the world points and the pixels";
  }
  else if (pixels->GetNumberOfComponents() != 2)
  {
    this->Error = "SetObservations: the pixels must have 2 components (u, v), not " +
      std::to_string(pixels->GetNumberOfComponents());
  }
  else if (pixels->GetNumberOfTuples() != world->GetNumberOfPoints())
  {
    this->Error = "SetObservations: " + std::to_string(world->GetNumberOfPoints()) +
      " world points but " + std::to_string(pixels->GetNumberOfTuples()) + " pixels";
  }
  else
  {
    this->World->DeepCopy(world);
    this->Pixels->SetNumberOfPoints(pixels->GetNumberOfTuples());
    for (vtkIdType i = 0; i < pixels->GetNumberOfTuples(); ++i)
    {
      this->Pixels->SetPoint(i, pixels->GetComponent(i, 0), pixels->GetComponent(i, 1), 0.0);
    }
  }
  this->Modified();
}

bool vtkCatadioptricPoseEstimator::Estimate()
{
  this->NumberOfInliers = 0;
  this->RMSError = 0.0;
  this->Inliers->Initialize();
  if (!this->Error.empty() && this->World->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< this->Error);
    return false;
  }
  if (!this->Camera)
  {
    this->Error = "No camera: call SetCamera()";
    vtkErrorMacro(<< this->Error);
    return false;
  }
  std::vector<catar::PoseObservation> observations;
  for (vtkIdType i = 0; i < this->World->GetNumberOfPoints(); ++i)
  {
    double w[3], p[3];
    this->World->GetPoint(i, w);
    this->Pixels->GetPoint(i, p);
    observations.push_back({ catar::Vec2(p[0], p[1]), catar::Vec3(w[0], w[1], w[2]) });
  }
  catar::PoseOptions options;
  options.inlierThreshold = this->InlierThreshold;
  options.maxIterations = this->MaximumIterations;
  options.seed = this->Seed;
  const catar::PoseResult result =
    catar::EstimatePose(this->Camera->GetModel(), observations, options);
  if (!result.ok)
  {
    this->Error = result.error;
    vtkErrorMacro(<< this->Error);
    return false;
  }
  this->Error.clear();
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      this->WorldToCamera->SetElement(r, c, result.worldToCamera(r, c));
    }
  }
  this->Inliers->SetNumberOfValues(static_cast<vtkIdType>(result.inliers.size()));
  for (std::size_t i = 0; i < result.inliers.size(); ++i)
  {
    this->Inliers->SetValue(static_cast<vtkIdType>(i), result.inliers[i]);
  }
  this->NumberOfInliers = result.inlierCount;
  this->RMSError = result.rmsPixels;
  this->Modified();
  return true;
}

vtkMatrix4x4* vtkCatadioptricPoseEstimator::GetWorldToCamera()
{
  return this->WorldToCamera;
}

vtkUnsignedCharArray* vtkCatadioptricPoseEstimator::GetInliers()
{
  return this->Inliers;
}

const char* vtkCatadioptricPoseEstimator::GetLastError()
{
  return this->Error.c_str();
}

void vtkCatadioptricPoseEstimator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera.Get() << "\n";
  os << indent << "Observations: " << this->World->GetNumberOfPoints() << "\n";
  os << indent << "InlierThreshold: " << this->InlierThreshold << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "NumberOfInliers: " << this->NumberOfInliers << "\n";
  os << indent << "RMSError: " << this->RMSError << "\n";
}
