#include "vtkCatadioptricImageSink.h"

#include "CameraModel.h" // kMaxImageSide, kMaxImagePixels
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricImageSupport.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <set>
#include <vector>

vtkCatadioptricImageSink::vtkCatadioptricImageSink()
{
  this->SetNumberOfInputPorts(3);
  this->SetColorArrayName(vtkCatadioptricArrayNames::Colors);
}

vtkCatadioptricImageSink::~vtkCatadioptricImageSink()
{
  this->SetColorArrayName(nullptr);
}

int vtkCatadioptricImageSink::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 1 ? "vtkPolyData" : "vtkImageData");
  if (port != 0)
  {
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkCatadioptricImageSink::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0, 0, 0, 0, 0, 0 };
  vtkInformation* frameInfo = inputVector[0]->GetInformationObject(0);
  if (frameInfo && frameInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    frameInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  }
  else
  {
    int size[2] = { 0, 0 };
    this->ImageSizeWithoutFrame(inputVector, size);
    extent[1] = std::max(1, size[0]) - 1;
    extent[3] = std::max(1, size[1]) - 1;
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  // Time: the union of the inputs' time steps (a frame source or projections that follow a
  // trajectory), so that the image plays with them.
  std::set<double> times;
  for (int port = 0; port < this->GetNumberOfInputPorts(); ++port)
  {
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
    {
      vtkInformation* in = inputVector[port]->GetInformationObject(i);
      const int n = in->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      const double* steps = in->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      for (int k = 0; k < n && steps; ++k)
      {
        times.insert(steps[k]);
      }
    }
  }
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (!times.empty())
  {
    const std::vector<double> steps(times.begin(), times.end());
    outInfo->Set(
      vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps.data(), static_cast<int>(steps.size()));
    const double range[2] = { steps.front(), steps.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

int vtkCatadioptricImageSink::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkCatadioptricImageSupport::RequestWholeExtents(inputVector, { 0, 2 });
  return 1;
}

void vtkCatadioptricImageSink::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)")
     << "\n";
  os << indent << "Color: " << this->Color[0] << " " << this->Color[1] << " " << this->Color[2]
     << "\n";
  os << indent << "Opacity: " << this->Opacity << "\n";
  os << indent << "BackgroundColor: " << this->BackgroundColor[0] << " " << this->BackgroundColor[1]
     << " " << this->BackgroundColor[2] << " " << this->BackgroundColor[3] << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " " << this->ImageSize[1] << "\n";
  os << indent << "RepeatTextures: " << (this->RepeatTextures ? "On" : "Off") << "\n";
  os << indent << "OutputVisibleTriangle: " << (this->OutputVisibleTriangle ? "On" : "Off") << "\n";
  os << indent << "OutputPathLength: " << (this->OutputPathLength ? "On" : "Off") << "\n";
}

int vtkCatadioptricImageSink::CheckFrame(vtkImageData* frame, int width, int height)
{
  if (!frame)
  {
    return 0;
  }
  int dims[3];
  frame->GetDimensions(dims);
  vtkDataArray* scalars = frame->GetPointData()->GetScalars();
  if (!scalars || scalars->GetDataType() != VTK_UNSIGNED_CHAR || dims[2] != 1)
  {
    vtkErrorMacro("The frame must be a 2D image of unsigned char scalars.");
    return -1;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components < 1 || components > 4)
  {
    vtkErrorMacro("The frame must have 1 to 4 components, not " << components << ".");
    return -1;
  }
  if (width > 0 && (dims[0] != width || dims[1] != height))
  {
    vtkErrorMacro("The frame is " << dims[0] << "x" << dims[1] << " but the camera image is "
                                  << width << "x" << height << ".");
    return -1;
  }
  // The pixels are read through the array's pointer: it must hold every pixel the extent says
  // (an array set shorter, from Python or C++, was read past its end).
  const vtkIdType pixels = static_cast<vtkIdType>(dims[0]) * dims[1];
  if (scalars->GetNumberOfTuples() < pixels)
  {
    vtkErrorMacro("The frame's scalars hold " << scalars->GetNumberOfTuples() << " pixels but its "
                                              << dims[0] << "x" << dims[1] << " extent has "
                                              << pixels << ".");
    return -1;
  }
  return components;
}

bool vtkCatadioptricImageSink::ResolveImageSize(bool haveFrame, int& width, int& height)
{
  if (!haveFrame && this->ImageSize[0] > 0 && this->ImageSize[1] > 0)
  {
    if (width > 0 && (this->ImageSize[0] != width || this->ImageSize[1] != height))
    {
      vtkErrorMacro("ImageSize " << this->ImageSize[0] << "x" << this->ImageSize[1]
                                 << " differs from the camera image " << width << "x" << height
                                 << ".");
      return false;
    }
    width = this->ImageSize[0];
    height = this->ImageSize[1];
  }
  if (width <= 0 || height <= 0)
  {
    vtkErrorMacro("No image size: connect a frame, a projected mesh, or set ImageSize.");
    return false;
  }
  if (width > catar::kMaxImageSide || height > catar::kMaxImageSide ||
    static_cast<long long>(width) * height > catar::kMaxImagePixels)
  {
    vtkErrorMacro("The image size " << width << "x" << height << " is over the limit of "
                                    << catar::kMaxImageSide << " pixels a side and "
                                    << catar::kMaxImagePixels << " pixels.");
    return false;
  }
  return true;
}
