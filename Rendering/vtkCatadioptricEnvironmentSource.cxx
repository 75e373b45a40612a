#include "vtkCatadioptricEnvironmentSource.h"

#include "Environment.h"
#include "Projector.h"

#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricParallel.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
// Width of the panorama generated from the room when PANORAMA mode has no file.
constexpr int kGeneratedPanoramaWidth = 2048;

// An 8-bit value of component `c` of tuple `t` of a non-unsigned-char array: integers scaled by
// their type's range, floating point (linear radiance) tone-mapped with c / (1 + c), gamma 2.2.
std::uint8_t ToByte(vtkDataArray* array, vtkIdType t, int c, bool floating, double scale)
{
  double v = array->GetComponent(t, c);
  if (!std::isfinite(v))
  {
    v = 0.0;
  }
  if (floating)
  {
    v = std::max(0.0, v);
    v = std::pow(v / (1.0 + v), 1.0 / 2.2);
  }
  else
  {
    v *= scale;
  }
  return static_cast<std::uint8_t>(std::lround(255.0 * std::min(1.0, std::max(0.0, v))));
}
} // namespace

// What PANORAMA mode draws: the panorama and what it was made from.
struct vtkCatadioptricEnvironmentSource::PanoramaCache
{
  catar::EquirectangularPanorama Panorama;
  bool Valid = false;
  std::string FileName; // "" for the generated one
  std::filesystem::file_time_type FileTime{};
  std::array<double, 10> RoomKey{}; // room corners, tile, viewpoint (generated panorama)
  unsigned long Generation = 0;     // counts the panoramas made: a frame names the one it used
};

// The last frame made and what it was made from: the output's pixel array (not held, so that the
// pipeline can reuse it in place; a weak pointer says whether it is still there), its MTime after
// writing, the camera and this source's parameters.
struct vtkCatadioptricEnvironmentSource::FrameCache
{
  vtkWeakPointer<vtkDataArray> Pixels;
  vtkMTimeType PixelsTime = 0;
  catar::CameraModel Camera;
  std::vector<double> Parameters;

  static bool SameCamera(const catar::CameraModel& a, const catar::CameraModel& b)
  {
    return a.SameLens(b) && a.mirror == b.mirror && a.worldToCamera == b.worldToCamera;
  }

  // Whether `output` still holds the frame made from `camera` and `parameters`.
  bool Holds(vtkImageData* output, const catar::CameraModel& camera,
    const std::vector<double>& parameters) const
  {
    vtkDataArray* scalars = output->GetPointData()->GetScalars();
    return scalars && scalars == this->Pixels.GetPointer() &&
      scalars->GetMTime() == this->PixelsTime && parameters == this->Parameters &&
      SameCamera(camera, this->Camera);
  }
};

vtkStandardNewMacro(vtkCatadioptricEnvironmentSource);

vtkCatadioptricEnvironmentSource::vtkCatadioptricEnvironmentSource()
  : Cache(new PanoramaCache)
  , LastFrame(new FrameCache)
{
  this->SetNumberOfInputPorts(0);
}

vtkCatadioptricEnvironmentSource::~vtkCatadioptricEnvironmentSource()
{
  this->SetPanoramaFileName(nullptr);
}

vtkCatadioptricCameraSlotMacro(vtkCatadioptricEnvironmentSource);
vtkCatadioptricCameraSlotValidMacro(vtkCatadioptricEnvironmentSource);
vtkCatadioptricCameraSlotTrajectoryMacro(vtkCatadioptricEnvironmentSource);

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
  std::string error;
  if (!this->CameraSlot.AnnounceTimeSteps(outInfo, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  return 1;
}

int vtkCatadioptricEnvironmentSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkCatadioptricCamera* camera = this->ResolveValidCamera(outputVector->GetInformationObject(0));
  if (!camera)
  {
    return 0;
  }
  const bool usesRoom = this->Mode == ROOM || !this->PanoramaFileName || !*this->PanoramaFileName;
  for (int k = 0; k < 3 && usesRoom; ++k)
  {
    if (!(this->RoomMinimum[k] < this->RoomMaximum[k]))
    {
      vtkErrorMacro("RoomMinimum must be below RoomMaximum on every axis.");
      return 0;
    }
  }
  if (this->Mode == PANORAMA && !this->UpdatePanorama(camera))
  {
    return 0;
  }
  const int width = camera->GetImageWidth();
  const int height = camera->GetImageHeight();
  vtkImageData* output = vtkImageData::GetData(outputVector);
  // The last frame again when nothing it depends on has changed (its pixels are still the
  // output's: the pipeline keeps an image's scalars from one update to the next).
  const std::vector<double> parameters = { static_cast<double>(this->Mode),
    static_cast<double>(this->Samples), this->RoomMinimum[0], this->RoomMinimum[1],
    this->RoomMinimum[2], this->RoomMaximum[0], this->RoomMaximum[1], this->RoomMaximum[2],
    this->FloorTileSize, this->PanoramaRotation, this->BackdropColor[0], this->BackdropColor[1],
    this->BackdropColor[2],
    this->Mode == PANORAMA ? static_cast<double>(this->Cache->Generation) : 0.0 };
  FrameCache& last = *this->LastFrame;
  if (last.Holds(output, camera->GetModel(), parameters))
  {
    output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
    output->SetOrigin(0, 0, 0);
    output->SetSpacing(1, 1, 1);
    return 1;
  }
  last.Pixels = nullptr;
  unsigned char* bytes = vtkCatadioptricImageSupport::AllocateRGBA(output, width, height);

  const catar::Projector projector(camera->GetModel());
  catar::RoomEnvironment room;
  room.minCorner = catar::Vec3(this->RoomMinimum[0], this->RoomMinimum[1], this->RoomMinimum[2]);
  room.maxCorner = catar::Vec3(this->RoomMaximum[0], this->RoomMaximum[1], this->RoomMaximum[2]);
  room.floorTile = this->FloorTileSize;
  catar::PanoramaPlacement placement;
  if (this->Mode == PANORAMA)
  {
    placement.rotation = this->PanoramaRotation;
    placement.backdrop =
      catar::Vec3(this->BackdropColor[0], this->BackdropColor[1], this->BackdropColor[2]);
  }
  catar::ImageView view;
  view.width = width;
  view.height = height;
  view.rowStride = -4 * static_cast<std::ptrdiff_t>(width);
  view.data = bytes + 4 * static_cast<std::ptrdiff_t>(width) * (height - 1);
  const int samples = this->Samples;
  const bool panorama = this->Mode == PANORAMA;
  const catar::EquirectangularPanorama& image = this->Cache->Panorama;
  vtkCatadioptricParallel::For(0, height, 8, [&](vtkIdType y0, vtkIdType y1) {
    if (panorama)
    {
      catar::RenderPanoramaRows(
        projector, image, placement, samples, view, static_cast<int>(y0), static_cast<int>(y1));
    }
    else
    {
      catar::RenderEnvironmentRows(
        projector, room, samples, view, static_cast<int>(y0), static_cast<int>(y1));
    }
  });
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  scalars->Modified(); // written through its pointer
  last.Pixels = scalars;
  last.PixelsTime = scalars->GetMTime();
  last.Camera = camera->GetModel();
  last.Parameters = parameters;
  return 1;
}

bool vtkCatadioptricEnvironmentSource::UpdatePanorama(vtkCatadioptricCamera* camera)
{
  PanoramaCache& cache = *this->Cache;
  const std::string name = this->PanoramaFileName ? this->PanoramaFileName : "";
  if (name.empty())
  {
    // The room seen from the mirror's viewpoint (a sphere's centre).
    const catar::Projector projector(camera->GetModel());
    if (!projector.GetMirror())
    {
      vtkErrorMacro("Invalid camera: " << projector.GetError());
      return false;
    }
    const catar::Vec3 viewpoint =
      projector.GetModel().CameraToWorld(projector.GetMirror()->Viewpoint());
    const std::array<double, 10> key = { this->RoomMinimum[0], this->RoomMinimum[1],
      this->RoomMinimum[2], this->RoomMaximum[0], this->RoomMaximum[1], this->RoomMaximum[2],
      this->FloorTileSize, viewpoint.x(), viewpoint.y(), viewpoint.z() };
    if (!cache.Valid || !cache.FileName.empty() || cache.RoomKey != key)
    {
      catar::RoomEnvironment room;
      room.minCorner = catar::Vec3(key[0], key[1], key[2]);
      room.maxCorner = catar::Vec3(key[3], key[4], key[5]);
      room.floorTile = key[6];
      catar::EquirectangularPanorama& pano = cache.Panorama;
      pano.width = kGeneratedPanoramaWidth;
      pano.height = kGeneratedPanoramaWidth / 2;
      pano.channels = 3;
      pano.pixels.resize(static_cast<std::size_t>(pano.width) * pano.height * pano.channels);
      vtkCatadioptricParallel::For(0, pano.height, 1, [&](vtkIdType j0, vtkIdType j1) {
        catar::RenderRoomPanoramaRows(
          room, viewpoint, pano, static_cast<int>(j0), static_cast<int>(j1));
      });
      cache.FileName.clear();
      cache.RoomKey = key;
      cache.Valid = true;
      ++cache.Generation;
    }
    return true;
  }

  std::error_code ec;
  const std::filesystem::file_time_type time = std::filesystem::last_write_time(name, ec);
  if (ec)
  {
    cache.Valid = false;
    vtkErrorMacro("PanoramaFileName: cannot read '" << name << "': " << ec.message());
    return false;
  }
  if (cache.Valid && cache.FileName == name && cache.FileTime == time)
  {
    return true;
  }
  cache.Valid = false;
  std::string readError;
  vtkSmartPointer<vtkImageData> input = vtkCatadioptricImageSupport::ReadImageFile(name, readError);
  if (!input)
  {
    vtkErrorMacro("PanoramaFileName: " << readError);
    return false;
  }
  vtkDataArray* scalars = input ? input->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (input)
  {
    input->GetDimensions(dims);
  }
  const int components = scalars ? scalars->GetNumberOfComponents() : 0;
  if (!scalars || dims[0] < 1 || dims[1] < 1 ||
    scalars->GetNumberOfTuples() < static_cast<vtkIdType>(dims[0]) * dims[1] || components < 1 ||
    components > 4)
  {
    vtkErrorMacro("PanoramaFileName: cannot read '" << name << "' (" << dims[0] << "x" << dims[1]
                                                    << " pixels, " << components << " components)");
    return false;
  }
  if (dims[0] != 2 * dims[1])
  {
    vtkWarningMacro("PanoramaFileName: '" << name << "' is " << dims[0] << "x" << dims[1]
                                          << ", not 2:1; it is stretched to the whole sphere");
  }

  // Core layout: rows from the top, RGB (grey and RGB inputs) or RGBA (with alpha).
  catar::EquirectangularPanorama& pano = cache.Panorama;
  pano.width = dims[0];
  pano.height = dims[1];
  pano.channels = (components == 2 || components == 4) ? 4 : 3;
  pano.pixels.assign(static_cast<std::size_t>(pano.width) * pano.height * pano.channels, 0);
  const bool grey = components < 3;
  const bool alpha = pano.channels == 4;
  vtkUnsignedCharArray* bytes = vtkUnsignedCharArray::SafeDownCast(scalars);
  const int type = scalars->GetDataType();
  const bool floating = type == VTK_FLOAT || type == VTK_DOUBLE;
  const double range = scalars->GetDataTypeMax();
  const double scale = floating || !(range > 0.0) ? 1.0 : 1.0 / range;
  vtkCatadioptricParallel::For(0, pano.height, 1, [&](vtkIdType j0, vtkIdType j1) {
    for (vtkIdType j = j0; j < j1; ++j)
    {
      const vtkIdType row = static_cast<vtkIdType>(pano.height - 1 - j) * pano.width; // VTK row
      for (int i = 0; i < pano.width; ++i)
      {
        const vtkIdType t = row + i;
        std::uint8_t c[4] = { 0, 0, 0, 0 };
        for (int k = 0; k < components && k < 4; ++k)
        {
          c[k] =
            bytes ? bytes->GetValue(t * components + k) : ToByte(scalars, t, k, floating, scale);
        }
        std::uint8_t* out = pano.texel(i, static_cast<int>(j));
        out[0] = c[0];
        out[1] = grey ? c[0] : c[1];
        out[2] = grey ? c[0] : c[2];
        if (alpha)
        {
          out[3] = c[components - 1];
        }
      }
    }
  });
  cache.FileName = name;
  cache.FileTime = time;
  cache.Valid = true;
  ++cache.Generation;
  return true;
}

void vtkCatadioptricEnvironmentSource::SetPanoramaRotation(double degrees)
{
  if (!std::isfinite(degrees))
  {
    vtkErrorMacro("PanoramaRotation must be a finite number of degrees, not " << degrees << ".");
    return;
  }
  if (this->PanoramaRotation != degrees)
  {
    this->PanoramaRotation = degrees;
    this->Modified();
  }
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
  os << indent << "Mode: " << (this->Mode == PANORAMA ? "PANORAMA" : "ROOM") << "\n";
  os << indent << "PanoramaFileName: "
     << (this->PanoramaFileName && *this->PanoramaFileName ? this->PanoramaFileName
                                                           : "(none: the room)")
     << "\n";
  os << indent << "PanoramaRotation: " << this->PanoramaRotation << "\n";
  os << indent << "BackdropColor: " << this->BackdropColor[0] << ", " << this->BackdropColor[1]
     << ", " << this->BackdropColor[2] << "\n";
}
