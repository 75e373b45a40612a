#include "vtkCatadioptricImageSupport.h"

#include "ImageFile.h"

#include "CameraModel.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricParallel.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "vtkFloatArray.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

void vtkCatadioptricImageSupport::RequestWholeExtents(
  vtkInformationVector** inputVector, std::initializer_list<int> ports)
{
  for (int port : ports)
  {
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
    {
      vtkInformation* info = inputVector[port]->GetInformationObject(i);
      if (info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
      {
        int extent[6];
        info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
        info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
      }
    }
  }
}

namespace
{
// Widens the pixels [b, e) of a frame of kComponents unsigned char values per pixel to RGBA.
template<int kComponents>
void Widen(const unsigned char* in, vtkIdType b, vtkIdType e, unsigned char* out)
{
  vtkIdType i = b;
  if (kComponents == 4)
  {
    std::copy(in + 4 * b, in + 4 * e, out + 4 * b);
    return;
  }
  const std::uint32_t one = 1;
  const bool littleEndian = *reinterpret_cast<const unsigned char*>(&one) == 1;
  if (kComponents == 3 && littleEndian)
  {
    // RGB, the camera's format, four pixels (three 32-bit words in, four out) at a time: about
    // twice as fast as byte by byte (measured), the frame being copied every frame.
    for (; i + 4 <= e; i += 4)
    {
      std::uint32_t w[3];
      std::memcpy(w, in + 3 * i, 12);
      const std::uint32_t a = 0xFF000000u;
      const std::uint32_t rgba[4] = { (w[0] & 0x00FFFFFFu) | a, (w[0] >> 24) | (w[1] << 8) | a,
        (w[1] >> 16) | (w[2] << 16) | a, (w[2] >> 8) | a };
      std::memcpy(out + 4 * i, rgba, 16);
    }
  }
  for (; i < e; ++i)
  {
    const unsigned char* s = in + kComponents * i;
    unsigned char* d = out + 4 * i;
    if (kComponents >= 3)
    {
      d[0] = s[0];
      d[1] = s[1];
      d[2] = s[2];
      d[3] = 255;
    }
    else
    {
      d[0] = d[1] = d[2] = s[0];
      d[3] = kComponents == 2 ? s[1] : 255;
    }
  }
}
} // namespace

void vtkCatadioptricImageSupport::CopyFrame(
  const unsigned char* in, int nc, vtkIdType n, unsigned char* out)
{
  vtkCatadioptricParallel::For(
    0, n, 1, [&](vtkIdType b, vtkIdType e) { CopyFramePixels(in, nc, b, e, out); });
}

void vtkCatadioptricImageSupport::CopyFramePixels(
  const unsigned char* in, int nc, vtkIdType b, vtkIdType e, unsigned char* out)
{
  switch (nc)
  {
    case 1:
      Widen<1>(in, b, e, out);
      break;
    case 2:
      Widen<2>(in, b, e, out);
      break;
    case 3:
      Widen<3>(in, b, e, out);
      break;
    default:
      Widen<4>(in, b, e, out);
      break;
  }
}

void vtkCatadioptricImageSupport::FillColor(const double rgba[4], vtkIdType n, unsigned char* out)
{
  vtkCatadioptricParallel::For(
    0, n, 1, [&](vtkIdType b, vtkIdType e) { FillColorPixels(rgba, b, e, out); });
}

void vtkCatadioptricImageSupport::FillColorPixels(
  const double rgba[4], vtkIdType b, vtkIdType e, unsigned char* out)
{
  unsigned char bg[4];
  for (int k = 0; k < 4; ++k)
  {
    bg[k] = static_cast<unsigned char>(std::lround(255.0 * std::min(1.0, std::max(0.0, rgba[k]))));
  }
  for (vtkIdType i = b; i < e; ++i)
  {
    std::copy(bg, bg + 4, out + 4 * i);
  }
}

bool vtkCatadioptricImageSupport::ReadTextures(vtkInformationVector* textures, bool repeat,
  std::vector<catar::TextureView>& views, std::string& error)
{
  views.clear();
  for (int t = 0; t < textures->GetNumberOfInformationObjects(); ++t)
  {
    vtkImageData* tex = vtkImageData::GetData(textures, t);
    vtkDataArray* texels = tex ? tex->GetPointData()->GetScalars() : nullptr;
    int dims[3] = { 0, 0, 0 };
    if (tex)
    {
      tex->GetDimensions(dims);
    }
    const int nc = texels ? texels->GetNumberOfComponents() : 0;
    if (!texels || texels->GetDataType() != VTK_UNSIGNED_CHAR || dims[2] != 1 || dims[0] < 1 ||
      dims[1] < 1 || !(nc == 1 || nc == 3 || nc == 4))
    {
      error = "Texture " + std::to_string(t) +
        " must be a 2D unsigned char image with 1, 3 or 4 components.";
      views.clear();
      return false;
    }
    catar::TextureView view;
    view.data = static_cast<const std::uint8_t*>(texels->GetVoidPointer(0));
    view.width = dims[0];
    view.height = dims[1];
    view.channels = nc;
    view.rowStride = static_cast<std::ptrdiff_t>(nc) * dims[0];
    view.repeat = repeat;
    views.push_back(view);
  }
  return true;
}

vtkDataArray* vtkCatadioptricImageSupport::TextureCoordinates(vtkPolyData* mesh)
{
  vtkDataArray* t = mesh->GetPointData()->GetTCoords();
  for (const char* name : { "TCoords", vtkCatadioptricArrayNames::TextureCoordinates })
  {
    if (!t)
    {
      t = mesh->GetPointData()->GetArray(name);
    }
  }
  return (t && t->GetNumberOfComponents() >= 2) ? t : nullptr;
}

vtkSmartPointer<vtkImageData> vtkCatadioptricImageSupport::ReadImageFile(
  const std::string& path, std::string& error)
{
  // A regular file (a FIFO would block, a device never end), whole, of a size the project
  // handles: checked before decoding.
  std::vector<unsigned char> bytes;
  catar::ImageHeader header;
  if (!catar::ReadImageFileBytes(path, bytes, header, error))
  {
    return nullptr;
  }
  cv::Mat image;
  try
  {
    image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  }
  catch (const cv::Exception& e)
  {
    error = "cannot read '" + path + "': " + e.msg;
    return nullptr;
  }
  if (image.empty() || image.dims != 2)
  {
    error = "'" + path + "' is not an image file that can be read (truncated, corrupt, or an " +
      "unknown format)";
    return nullptr;
  }
  if (static_cast<long long>(image.cols) * image.rows > catar::kMaxImagePixels)
  {
    error = "'" + path + "' is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
      " pixels, over the limit of " + std::to_string(catar::kMaxImagePixels) + " pixels";
    return nullptr;
  }
  const int channels = image.channels();
  if (channels < 1 || channels > 4)
  {
    error = "'" + path + "' has " + std::to_string(channels) + " channels (1 to 4 are read)";
    return nullptr;
  }
  // OpenCV's BGR(A) to RGB(A).
  if (channels == 3)
  {
    cv::cvtColor(image, image, cv::COLOR_BGR2RGB);
  }
  else if (channels == 4)
  {
    cv::cvtColor(image, image, cv::COLOR_BGRA2RGBA);
  }
  vtkSmartPointer<vtkDataArray> scalars;
  switch (image.depth())
  {
    case CV_8U:
      scalars = vtkSmartPointer<vtkUnsignedCharArray>::New();
      break;
    case CV_16U:
      scalars = vtkSmartPointer<vtkUnsignedShortArray>::New();
      break;
    case CV_32F:
      scalars = vtkSmartPointer<vtkFloatArray>::New();
      break;
    default:
      image.convertTo(image, CV_32F);
      scalars = vtkSmartPointer<vtkFloatArray>::New();
  }
  scalars->SetName("ImageFile");
  scalars->SetNumberOfComponents(channels);
  vtkCatadioptricAllocation::Tuples(scalars, static_cast<vtkIdType>(image.cols) * image.rows);
  const size_t rowBytes = static_cast<size_t>(image.cols) * image.elemSize();
  auto* out = static_cast<unsigned char*>(scalars->GetVoidPointer(0));
  for (int j = 0; j < image.rows; ++j)
  {
    // VTK's row 0 is the bottom one.
    std::memcpy(out + rowBytes * (image.rows - 1 - j), image.ptr(j), rowBytes);
  }
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->SetDimensions(image.cols, image.rows, 1);
  result->GetPointData()->SetScalars(scalars);
  return result;
}

bool vtkCatadioptricImageSupport::TextureIndex(vtkPolyData* mesh, int& index, std::string& error)
{
  index = 0;
  vtkDataArray* array = mesh->GetFieldData()->GetArray(vtkCatadioptricArrayNames::TextureIndex);
  if (!array)
  {
    return true;
  }
  if (array->GetNumberOfTuples() < 1 || array->GetNumberOfComponents() < 1)
  {
    error = "the field data array TextureIndex is empty (give one integer, -1 for no texture).";
    return false;
  }
  const double v = array->GetComponent(0, 0);
  if (!(v == std::floor(v) && v >= -2147483648.0 && v <= 2147483647.0))
  {
    error = "the field data array TextureIndex holds " + std::to_string(v) + ", not an integer.";
    return false;
  }
  index = static_cast<int>(v);
  return true;
}

unsigned char* vtkCatadioptricImageSupport::AllocateRGBA(
  vtkImageData* output, int width, int height)
{
  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->SetOrigin(0, 0, 0);
  output->SetSpacing(1, 1, 1);
  // vtkImageData keeps its scalars through the pipeline's PrepareForNewData and AllocateScalars
  // reuses them when no one else holds them: the image is not allocated again every frame.
  vtkCatadioptricAllocation::Scalars(output, VTK_UNSIGNED_CHAR, 4);
  vtkUnsignedCharArray* scalars =
    vtkUnsignedCharArray::SafeDownCast(output->GetPointData()->GetScalars());
  scalars->SetName(vtkCatadioptricArrayNames::RGBA);
  return scalars->GetPointer(0);
}

catar::Frame vtkCatadioptricImageSupport::ToFrame(vtkImageData* image)
{
  catar::Frame f;
  int dims[3] = { 0, 0, 0 };
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfComponents() != 4 ||
    scalars->GetDataType() != VTK_UNSIGNED_CHAR || dims[0] <= 0 || dims[1] <= 0)
  {
    return f;
  }
  f.width = dims[0];
  f.height = dims[1];
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  const std::size_t row = static_cast<std::size_t>(f.width) * 4;
  f.rgba.resize(row * f.height);
  for (int y = 0; y < f.height; ++y)
  {
    std::copy(p + row * (f.height - 1 - y), p + row * (f.height - y), f.rgba.data() + row * y);
  }
  return f;
}

void vtkCatadioptricImageSupport::FromFrame(const catar::Frame& frame, vtkImageData* image)
{
  image->SetDimensions(frame.width, frame.height, 1);
  vtkCatadioptricAllocation::Scalars(image, VTK_UNSIGNED_CHAR, 4);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  const std::size_t row = static_cast<std::size_t>(frame.width) * 4;
  for (int y = 0; y < frame.height; ++y)
  {
    std::copy(frame.rgba.data() + row * (frame.height - 1 - y),
      frame.rgba.data() + row * (frame.height - y), out + row * y);
  }
  image->Modified();
}
