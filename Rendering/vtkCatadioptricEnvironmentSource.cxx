#include "vtkCatadioptricEnvironmentSource.h"

#include "Environment.h"
#include "SphereProjection.h"

#include "vtkCatadioptricCamera.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

vtkStandardNewMacro(vtkCatadioptricEnvironmentSource);

vtkCatadioptricEnvironmentSource::vtkCatadioptricEnvironmentSource()
{
  this->SetNumberOfInputPorts(0);
}

vtkCatadioptricEnvironmentSource::~vtkCatadioptricEnvironmentSource() = default;

vtkCatadioptricCameraSlotMacro(vtkCatadioptricEnvironmentSource);

int vtkCatadioptricEnvironmentSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkCatadioptricCamera* camera = this->ResolveCamera();
  if (!camera)
  {
    return 0;
  }
  int extent[6] = { 0, camera->GetImageWidth() - 1, 0, camera->GetImageHeight() - 1, 0, 0 };
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

int vtkCatadioptricEnvironmentSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkCatadioptricCamera* camera = this->ResolveCamera();
  if (!camera)
  {
    return 0;
  }
  if (!camera->IsValid())
  {
    vtkErrorMacro("Invalid camera: " << camera->GetLastError());
    return 0;
  }
  for (int k = 0; k < 3; ++k)
  {
    if (!(this->RoomMinimum[k] < this->RoomMaximum[k]))
    {
      vtkErrorMacro("RoomMinimum must be below RoomMaximum on every axis.");
      return 0;
    }
  }
  const int width = camera->GetImageWidth();
  const int height = camera->GetImageHeight();
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->SetOrigin(0, 0, 0);
  output->SetSpacing(1, 1, 1);
  output->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  vtkUnsignedCharArray* scalars =
    vtkUnsignedCharArray::SafeDownCast(output->GetPointData()->GetScalars());
  scalars->SetName("RGBA");

  const catar::SphereProjector projector(camera->GetModel());
  catar::RoomEnvironment room;
  room.minCorner = catar::Vec3(this->RoomMinimum[0], this->RoomMinimum[1], this->RoomMinimum[2]);
  room.maxCorner = catar::Vec3(this->RoomMaximum[0], this->RoomMaximum[1], this->RoomMaximum[2]);
  room.floorTile = this->FloorTileSize;
  catar::ImageView view;
  view.width = width;
  view.height = height;
  view.rowStride = -4 * static_cast<std::ptrdiff_t>(width);
  view.data = scalars->GetPointer(0) + 4 * static_cast<std::ptrdiff_t>(width) * (height - 1);
  const int samples = this->Samples;
  vtkSMPTools::For(0, height, 8, [&](vtkIdType y0, vtkIdType y1) {
    catar::RenderEnvironmentRows(
      projector, room, samples, view, static_cast<int>(y0), static_cast<int>(y1));
  });
  return 1;
}

void vtkCatadioptricEnvironmentSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->CameraSlot.GetCamera() << "\n";
  const char* file = this->CameraSlot.GetCalibrationFileName();
  os << indent << "CalibrationFileName: " << (file ? file : "(none)") << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "RoomMinimum: " << this->RoomMinimum[0] << ", " << this->RoomMinimum[1] << ", "
     << this->RoomMinimum[2] << "\n";
  os << indent << "RoomMaximum: " << this->RoomMaximum[0] << ", " << this->RoomMaximum[1] << ", "
     << this->RoomMaximum[2] << "\n";
  os << indent << "FloorTileSize: " << this->FloorTileSize << "\n";
}
