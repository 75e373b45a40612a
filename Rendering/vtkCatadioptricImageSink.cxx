#include "vtkCatadioptricImageSink.h"

#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

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
}
