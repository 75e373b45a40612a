#include "vtkCatadioptricSceneReader.h"

#include "ConfigReader.h"
#include "SceneDescription.h"

#include "vtkCallbackCommand.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricSceneReader);

vtkCatadioptricSceneReader::vtkCatadioptricSceneReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
  // The renderer's progress becomes the reader's; its errors are reported by the reader (an
  // observer of ErrorEvent keeps VTK from printing them a second time).
  this->Observer->SetClientData(this);
  this->Observer->SetCallback(&vtkCatadioptricSceneReader::OnRendererEvent);
  this->Renderer->AddObserver(vtkCommand::ProgressEvent, this->Observer);
  this->Renderer->AddObserver(vtkCommand::ErrorEvent, this->Observer);
}

vtkCatadioptricSceneReader::~vtkCatadioptricSceneReader()
{
  this->SetFileName(nullptr);
}

void vtkCatadioptricSceneReader::OnRendererEvent(
  vtkObject*, unsigned long event, void* clientData, void* callData)
{
  auto* self = static_cast<vtkCatadioptricSceneReader*>(clientData);
  if (event == vtkCommand::ProgressEvent && callData)
  {
    self->SetProgressText(self->Renderer->GetProgressText());
    self->UpdateProgress(*static_cast<double*>(callData));
  }
}

vtkCatadioptricSceneRenderer* vtkCatadioptricSceneReader::GetRenderer()
{
  return this->Renderer;
}

int vtkCatadioptricSceneReader::CanReadFile(const char* fileName)
{
  if (!fileName || !*fileName)
  {
    return 0;
  }
  catar::fs::Node root;
  std::string error;
  if (!catar::fs::Parse(catar::FindDataFile("", fileName), false, "scene", root, error))
  {
    return 0;
  }
  return root.isMap() && (!root["camera"].empty() || !root["objects"].empty()) ? 1 : 0;
}

vtkImageData* vtkCatadioptricSceneReader::GetImageOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkMultiBlockDataSet* vtkCatadioptricSceneReader::GetObjectsOutput()
{
  return vtkMultiBlockDataSet::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkCatadioptricSceneReader::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkMultiBlockDataSet");
  return 1;
}

vtkTypeBool vtkCatadioptricSceneReader::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inInfo, vtkInformationVector* outInfo)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(request, inInfo, outInfo);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inInfo, outInfo);
  }
  return this->Superclass::ProcessRequest(request, inInfo, outInfo);
}

bool vtkCatadioptricSceneReader::Load()
{
  // Nothing changed since the last reading: its result (its error was reported then).
  if (this->LoadTime > this->GetMTime())
  {
    return this->Loaded;
  }
  this->Loaded = false;
  this->LoadTime.Modified();
  if (!this->FileName || !*this->FileName)
  {
    this->LoadError = "no scene file given (FileName)";
    vtkErrorMacro(<< this->LoadError);
    return false;
  }
  // As catadioptric-render: a name not found as given is looked for on the data search path.
  const std::string name = catar::FindDataFile("", this->FileName);
  vtkCatadioptricSceneRenderer* renderer = this->Renderer;
  renderer->SetSceneFileName(name.c_str());
  renderer->SetRemeshTargetArea(this->RemeshTargetArea);
  renderer->SetRemeshPixelTolerance(this->RemeshPixelTolerance);
  renderer->SetReferenceSamples(this->ReferenceSamples);
  renderer->SetTransparentBackground(this->TransparentBackground);
  this->SetProgressText("reading the scene");
  this->UpdateProgress(0.0);
  const bool ok = renderer->LoadScene();
  this->UpdateProgress(1.0);
  this->SetProgressText(nullptr);
  if (!ok)
  {
    this->LoadError = renderer->GetLastError();
    vtkErrorMacro(<< this->LoadError);
    return false;
  }
  this->LoadError.clear();
  this->Loaded = true;
  return true;
}

namespace
{
// The times announced for the renderer's frames: its frames' own times when they increase, else
// the frame numbers (a time step must come after the one before it). Empty for a still scene.
std::vector<double> FrameTimes(vtkCatadioptricSceneRenderer* renderer)
{
  const int n = renderer->GetNumberOfFrames();
  std::vector<double> times;
  if (n < 2)
  {
    return times;
  }
  bool increasing = true;
  for (int k = 0; k < n; ++k)
  {
    times.push_back(renderer->GetFrameTime(k));
    increasing = increasing && std::isfinite(times.back()) && (k == 0 || times[k] > times[k - 1]);
  }
  if (!increasing)
  {
    for (int k = 0; k < n; ++k)
    {
      times[k] = k;
    }
  }
  return times;
}
} // namespace

int vtkCatadioptricSceneReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* imageInfo = outputVector->GetInformationObject(0);
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* info = outputVector->GetInformationObject(port);
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  if (!this->Load())
  {
    // An empty image, so that views ask for nothing.
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 0;
  }
  vtkCatadioptricCamera* camera = this->Renderer->GetCamera();
  const int extent[6] = { 0, camera->GetImageWidth() - 1, 0, camera->GetImageHeight() - 1, 0, 0 };
  imageInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = { 1.0, 1.0, 1.0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  imageInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  imageInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(imageInfo, VTK_UNSIGNED_CHAR, 4);
  const std::vector<double> times = FrameTimes(this->Renderer);
  if (!times.empty())
  {
    const double range[2] = { times.front(), times.back() };
    for (int port = 0; port < 2; ++port)
    {
      vtkInformation* info = outputVector->GetInformationObject(port);
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
        static_cast<int>(times.size()));
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    }
  }
  return 1;
}

int vtkCatadioptricSceneReader::RequestData(
  vtkInformation* request, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  vtkMultiBlockDataSet* objects = vtkMultiBlockDataSet::GetData(outputVector, 1);
  if (!image || !objects)
  {
    vtkErrorMacro("The outputs are missing.");
    return 0;
  }
  image->Initialize();
  objects->Initialize();
  if (!this->Load())
  {
    return 0; // said when the scene was read
  }
  // The frame: the last one whose time is not after the time asked for (of the port asked
  // for), the first before the first.
  const std::vector<double> times = FrameTimes(this->Renderer);
  int frame = 0;
  int port = request->Has(vtkDemandDrivenPipeline::FROM_OUTPUT_PORT())
    ? request->Get(vtkDemandDrivenPipeline::FROM_OUTPUT_PORT())
    : 0;
  port = port >= 0 && port < 2 ? port : 0;
  vtkInformation* asked = outputVector->GetInformationObject(port);
  if (!times.empty() && asked->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    const double t = asked->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    // A little slack: a time step given back as text may have lost its last bits.
    const double slack = 1e-9 * std::max(1.0, std::abs(t));
    for (std::size_t k = 1; k < times.size() && times[k] <= t + slack; ++k)
    {
      frame = static_cast<int>(k);
    }
  }
  if (this->GetAbortExecute())
  {
    return 1;
  }
  this->SetProgressText("rendering");
  this->UpdateProgress(0.0);
  const bool ok = this->Renderer->RenderFrame(frame);
  this->UpdateProgress(1.0);
  this->SetProgressText(nullptr);
  if (!ok)
  {
    vtkErrorMacro(<< this->Renderer->GetLastError());
    return 0;
  }
  this->CurrentFrame = frame;

  // Port 0: the frame (a copy: the renderer draws the next frame into its own image).
  vtkImageData* drawn = this->Renderer->GetOutput();
  if (drawn)
  {
    image->DeepCopy(drawn);
  }
  // Port 1: the objects, one block each, named.
  const int n = this->Renderer->GetNumberOfObjects();
  objects->SetNumberOfBlocks(static_cast<unsigned int>(n));
  for (int i = 0; i < n; ++i)
  {
    vtkPolyData* mesh = this->Renderer->GetObjectMesh(i);
    vtkNew<vtkPolyData> block;
    if (mesh)
    {
      block->ShallowCopy(mesh);
    }
    // The renderer's bookkeeping, not the object's.
    block->GetFieldData()->RemoveArray(vtkCatadioptricArrayNames::TextureIndex);
    objects->SetBlock(static_cast<unsigned int>(i), block);
    objects->GetMetaData(static_cast<unsigned int>(i))
      ->Set(vtkCompositeDataSet::NAME(), this->Renderer->GetObjectName(i));
  }
  if (!times.empty())
  {
    image->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), times[frame]);
    objects->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), times[frame]);
  }
  return 1;
}

void vtkCatadioptricSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "RemeshTargetArea: " << this->RemeshTargetArea << "\n";
  os << indent << "RemeshPixelTolerance: " << this->RemeshPixelTolerance << "\n";
  os << indent << "ReferenceSamples: " << this->ReferenceSamples << "\n";
  os << indent << "TransparentBackground: " << (this->TransparentBackground ? "On" : "Off") << "\n";
  os << indent << "CurrentFrame: " << this->CurrentFrame << "\n";
}
