#include "vtkCatadioptricCompositor.h"

#include "Rasterizer.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricColorArray.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricCompositor);

namespace
{
struct Triangle
{
  catar::RasterVertex V[3];
  double Depth;
  double YMin;
  double YMax;
  int Texture;        // index into the textures, -1 for none
  bool Opaque;        // DEPTH_BUFFER: drawn in the first pass, writes depth
  catar::RasterId Id; // meshIndex * 2^32 + cellId (OutputVisibleTriangle)
};

// The bands of RequestData with a depth buffer (depth: width x height floats, top row first, or
// null) and/or an id buffer (ids: the output array, VTK row order, or null). Each band initialises
// its own rows of both buffers. In depth mode the opaque triangles come first and write depth; the
// others only test it.
void DrawWithBuffers(const catar::ImageView& view, const std::vector<Triangle>& triangles,
  const std::vector<catar::TextureView>& textures, int bandHeight, float* depth,
  catar::RasterId* ids)
{
  const int width = view.width;
  const int height = view.height;
  const std::ptrdiff_t w = width;
  const bool depthMode = depth != nullptr;
  catar::DepthView write;
  if (depthMode)
  {
    write.data = depth;
    write.width = width;
    write.height = height;
    write.rowStride = w;
  }
  catar::DepthView test = write;
  test.write = false;
  catar::IdView idView;
  if (ids)
  {
    idView.data = ids + w * (height - 1); // top row (y = 0) is the last VTK row
    idView.width = width;
    idView.height = height;
    idView.rowStride = -w;
  }
  const int nBands = (height + bandHeight - 1) / bandHeight;
  vtkSMPTools::For(0, nBands, 1, [&](vtkIdType b0, vtkIdType b1) {
    for (vtkIdType b = b0; b < b1; ++b)
    {
      const catar::PixelRect band{ 0, static_cast<int>(b * bandHeight), width,
        static_cast<int>(std::min<vtkIdType>(height, (b + 1) * bandHeight)) };
      for (int y = band.y0; y < band.y1; ++y)
      {
        if (depthMode)
        {
          std::fill(write.at(0, y), write.at(0, y) + width, std::numeric_limits<float>::infinity());
        }
        if (ids)
        {
          std::fill(idView.at(0, y), idView.at(0, y) + width, catar::RasterId(-1));
        }
      }
      for (const Triangle& t : triangles)
      {
        if (t.YMax < band.y0 - 0.5 || t.YMin > band.y1 - 0.5)
        {
          continue;
        }
        catar::rasterizeTriangle(view, t.V[0], t.V[1], t.V[2], band,
          depthMode ? (t.Opaque ? &write : &test) : nullptr,
          t.Texture >= 0 ? &textures[t.Texture] : nullptr, ids ? &idView : nullptr, t.Id);
      }
    }
  });
}
} // namespace

vtkCatadioptricCompositor::vtkCatadioptricCompositor()
{
  this->SetNumberOfInputPorts(3);
  this->SetColorArrayName("Colors");
}

vtkCatadioptricCompositor::~vtkCatadioptricCompositor()
{
  this->SetColorArrayName(nullptr);
}

int vtkCatadioptricCompositor::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  }
  else if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkCatadioptricCompositor::RequestInformation(
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
    // Without a frame the size is only known once the meshes' cameras are read; announce the
    // best guess (ImageSize, or the last size) and set the real extent in RequestData.
    const int w = this->ImageSize[0] > 0 ? this->ImageSize[0] : std::max(1, this->LastSize[0]);
    const int h = this->ImageSize[1] > 0 ? this->ImageSize[1] : std::max(1, this->LastSize[1]);
    extent[1] = w - 1;
    extent[3] = h - 1;
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

int vtkCatadioptricCompositor::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The whole frame and whole textures are always needed, whatever the output's extent.
  vtkCatadioptricImageSupport::RequestWholeExtents(inputVector, { 0, 2 });
  return 1;
}

int vtkCatadioptricCompositor::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkImageData* frame = vtkImageData::GetData(inputVector[0]);
  const int nMeshes = inputVector[1]->GetNumberOfInformationObjects();
  const bool depthMode = this->Visibility == DEPTH_BUFFER;
  const bool wantIds = this->OutputVisibleTriangle;
  this->NumberOfDrawnTriangles = 0;
  this->NumberOfSkippedTriangles = 0;

  // Image size: from the meshes' cameras, which must agree with each other and with the frame.
  int width = 0;
  int height = 0;
  vtkNew<vtkCatadioptricCamera> camera;
  for (int m = 0; m < nMeshes; ++m)
  {
    vtkPolyData* mesh = vtkPolyData::GetData(inputVector[1], m);
    if (!mesh || mesh->GetNumberOfPoints() == 0)
    {
      continue;
    }
    if (!camera->ReadFromFieldData(mesh->GetFieldData()))
    {
      vtkErrorMacro("Mesh " << m << ": " << camera->GetLastError());
      return 0;
    }
    if (width == 0)
    {
      width = camera->GetImageWidth();
      height = camera->GetImageHeight();
    }
    else if (width != camera->GetImageWidth() || height != camera->GetImageHeight())
    {
      vtkErrorMacro("Mesh " << m << " was projected for a " << camera->GetImageWidth() << "x"
                            << camera->GetImageHeight() << " image, mesh 0 for " << width << "x"
                            << height << ".");
      return 0;
    }
  }
  int frameComponents = 0;
  if (frame)
  {
    int dims[3];
    frame->GetDimensions(dims);
    vtkDataArray* scalars = frame->GetPointData()->GetScalars();
    if (!scalars || scalars->GetDataType() != VTK_UNSIGNED_CHAR || dims[2] != 1)
    {
      vtkErrorMacro("The frame must be a 2D image of unsigned char scalars.");
      return 0;
    }
    frameComponents = scalars->GetNumberOfComponents();
    if (frameComponents < 1 || frameComponents > 4)
    {
      vtkErrorMacro("The frame must have 1 to 4 components, not " << frameComponents << ".");
      return 0;
    }
    if (width != 0 && (dims[0] != width || dims[1] != height))
    {
      vtkErrorMacro("The frame is " << dims[0] << "x" << dims[1] << " but the camera image is "
                                    << width << "x" << height << ".");
      return 0;
    }
    width = dims[0];
    height = dims[1];
  }
  if (this->ImageSize[0] > 0 && this->ImageSize[1] > 0 && !frame)
  {
    if (width != 0 && (this->ImageSize[0] != width || this->ImageSize[1] != height))
    {
      vtkErrorMacro("ImageSize " << this->ImageSize[0] << "x" << this->ImageSize[1]
                                 << " differs from the camera image " << width << "x" << height
                                 << ".");
      return 0;
    }
    width = this->ImageSize[0];
    height = this->ImageSize[1];
  }
  if (width <= 0 || height <= 0)
  {
    vtkErrorMacro("No image size: connect a frame, a projected mesh, or set ImageSize.");
    return 0;
  }
  this->LastSize[0] = width;
  this->LastSize[1] = height;

  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->SetOrigin(0, 0, 0);
  output->SetSpacing(1, 1, 1);
  output->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  vtkUnsignedCharArray* outScalars =
    vtkUnsignedCharArray::SafeDownCast(output->GetPointData()->GetScalars());
  outScalars->SetName("RGBA");
  unsigned char* out = outScalars->GetPointer(0);
  const vtkIdType nPixels = static_cast<vtkIdType>(width) * height;

  // Background: the frame (grey and RGB widened to RGBA), or a colour.
  if (frame)
  {
    vtkCatadioptricImageSupport::CopyFrame(
      static_cast<const unsigned char*>(frame->GetPointData()->GetScalars()->GetVoidPointer(0)),
      frameComponents, nPixels, out);
  }
  else
  {
    vtkCatadioptricImageSupport::FillColor(this->BackgroundColor, nPixels, out);
  }
  this->UpdateProgress(0.2);

  // Textures (port 2): unsigned char images, 1, 3 or 4 components, row 0 at the bottom.
  std::vector<catar::TextureView> textures;
  std::string textureError;
  if (!vtkCatadioptricImageSupport::ReadTextures(
        inputVector[2], this->RepeatTextures, textures, textureError))
  {
    vtkErrorMacro(<< textureError);
    return 0;
  }
  // DEPTH_BUFFER: an RGBA texture is opaque when every alpha byte is 255.
  std::vector<char> opaqueTexture(textures.size(), 1);
  if (depthMode)
  {
    for (size_t t = 0; t < textures.size(); ++t)
    {
      const catar::TextureView& v = textures[t];
      if (v.channels != 4)
      {
        continue;
      }
      const vtkIdType n = static_cast<vtkIdType>(v.width) * v.height;
      for (vtkIdType i = 0; i < n && opaqueTexture[t]; ++i)
      {
        opaqueTexture[t] = v.data[4 * i + 3] == 255;
      }
    }
  }

  // Triangles in painter order.
  std::vector<Triangle> triangles;
  for (int m = 0; m < nMeshes; ++m)
  {
    vtkPolyData* mesh = vtkPolyData::GetData(inputVector[1], m);
    if (!mesh || mesh->GetNumberOfPolys() == 0)
    {
      continue;
    }
    vtkDataArray* pixels = mesh->GetPointData()->GetArray("ImageCoordinates");
    vtkDataArray* visible = mesh->GetCellData()->GetArray("Visible");
    vtkDataArray* depth = mesh->GetCellData()->GetArray("CentroidDepth");
    if (!pixels || pixels->GetNumberOfComponents() != 2 || !visible || !depth)
    {
      vtkErrorMacro("Mesh " << m
                            << " lacks ImageCoordinates/Visible/CentroidDepth: run "
                               "vtkCatadioptricProjection first.");
      return 0;
    }
    // DEPTH_BUFFER: the per-vertex depth.
    vtkDataArray* pathLength = nullptr;
    if (depthMode)
    {
      pathLength = mesh->GetPointData()->GetArray("PathLength");
      if (!pathLength || pathLength->GetNumberOfComponents() != 1 ||
        pathLength->GetNumberOfTuples() != mesh->GetNumberOfPoints())
      {
        vtkErrorMacro("Mesh " << m
                              << " has no PathLength point array (1 component, one value per "
                                 "point), which Visibility DEPTH_BUFFER needs: run "
                                 "vtkCatadioptricProjection first, or use PAINTER.");
        return 0;
      }
    }
    // OutputVisibleTriangle: the cells' original ids, when the mesh has them.
    vtkDataArray* originalIds = nullptr;
    if (wantIds)
    {
      originalIds = mesh->GetCellData()->GetArray("OriginalCellId");
      if (originalIds &&
        (originalIds->GetNumberOfComponents() != 1 ||
          originalIds->GetNumberOfTuples() != mesh->GetNumberOfCells()))
      {
        vtkErrorMacro("Mesh " << m
                              << ": the cell array OriginalCellId must have 1 component and one "
                                 "value per cell.");
        return 0;
      }
    }
    const catar::RasterId meshKey = static_cast<catar::RasterId>(m) << 32;
    const float solid[4] = { static_cast<float>(this->Color[0]), static_cast<float>(this->Color[1]),
      static_cast<float>(this->Color[2]), 1.0f };
    const vtkCatadioptricColorArray color(mesh, this->ColorArrayName, solid);
    if (color.HasArray() && color.GetNumberOfComponents() < 1)
    {
      vtkErrorMacro("Colour array " << this->ColorArrayName << " has no components.");
      return 0;
    }
    const float opacity = static_cast<float>(this->Opacity);
    // Texture: the one the mesh names in field data (TextureIndex), else the first, when the mesh
    // has texture coordinates.
    // A negative TextureIndex leaves the mesh untextured.
    vtkDataArray* tcoords =
      textures.empty() ? nullptr : vtkCatadioptricImageSupport::TextureCoordinates(mesh);
    int texture = -1;
    if (tcoords)
    {
      texture = 0;
      if (vtkDataArray* index = mesh->GetFieldData()->GetArray("TextureIndex"))
      {
        texture = static_cast<int>(index->GetComponent(0, 0));
      }
      if (texture < 0)
      {
        tcoords = nullptr;
        texture = -1;
      }
      else if (texture >= static_cast<int>(textures.size()))
      {
        vtkErrorMacro("Mesh " << m << " asks for texture " << texture << " but " << textures.size()
                              << " are connected.");
        return 0;
      }
    }
    const vtkIdType first = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
    vtkCellArray* polys = mesh->GetPolys();
    vtkNew<vtkIdList> ids;
    const vtkIdType nPolys = polys->GetNumberOfCells();
    triangles.reserve(triangles.size() + static_cast<size_t>(nPolys));
    for (vtkIdType c = 0; c < nPolys; ++c)
    {
      const vtkIdType cellId = first + c;
      polys->GetCellAtId(c, ids);
      const vtkIdType n = ids->GetNumberOfIds();
      if (n < 3 || visible->GetComponent(cellId, 0) == 0)
      {
        this->NumberOfSkippedTriangles += std::max<vtkIdType>(0, n - 2);
        continue;
      }
      auto vertex = [&](vtkIdType pid, catar::RasterVertex& v) {
        double px[2];
        pixels->GetTuple(pid, px);
        v.x = px[0];
        v.y = px[1];
        float rgba[4];
        color.Get(pid, cellId, rgba);
        v.r = rgba[0];
        v.g = rgba[1];
        v.b = rgba[2];
        v.a = rgba[3] * opacity;
        if (tcoords)
        {
          v.u = static_cast<float>(tcoords->GetComponent(pid, 0));
          v.v = static_cast<float>(tcoords->GetComponent(pid, 1));
        }
        if (pathLength)
        {
          v.depth = static_cast<float>(pathLength->GetComponent(pid, 0));
        }
      };
      catar::RasterId id = 0;
      if (wantIds)
      {
        const double original = originalIds ? originalIds->GetComponent(cellId, 0) : 0.0;
        id = meshKey +
          (originalIds ? static_cast<catar::RasterId>(original)
                       : static_cast<catar::RasterId>(cellId));
      }
      // Fan triangulation of polygons.
      for (vtkIdType k = 1; k + 1 < n; ++k)
      {
        Triangle t;
        vertex(ids->GetId(0), t.V[0]);
        vertex(ids->GetId(k), t.V[1]);
        vertex(ids->GetId(k + 1), t.V[2]);
        t.Depth = depth->GetComponent(cellId, 0);
        t.YMin = std::min({ t.V[0].y, t.V[1].y, t.V[2].y });
        t.YMax = std::max({ t.V[0].y, t.V[1].y, t.V[2].y });
        t.Texture = texture;
        t.Opaque = t.V[0].a >= 1.0f && t.V[1].a >= 1.0f && t.V[2].a >= 1.0f &&
          (texture < 0 || opaqueTexture[texture]);
        t.Id = id;
        triangles.push_back(t);
      }
    }
  }
  if (nMeshes > 1)
  {
    // One far-to-near order across meshes; each mesh keeps its own order among equal depths.
    std::stable_sort(triangles.begin(), triangles.end(),
      [](const Triangle& a, const Triangle& b) { return a.Depth > b.Depth; });
  }
  if (depthMode)
  {
    // Opaque triangles first (they write depth), then the semi-transparent ones in painter order.
    std::stable_partition(
      triangles.begin(), triangles.end(), [](const Triangle& t) { return t.Opaque; });
  }
  this->UpdateProgress(0.4);

  // Rasterise in horizontal bands in parallel; each band draws every triangle that meets it, in
  // order, so the painter order holds within every pixel.
  catar::ImageView view;
  view.width = width;
  view.height = height;
  view.rowStride = -4 * static_cast<std::ptrdiff_t>(width);
  view.data = out + 4 * static_cast<std::ptrdiff_t>(width) * (height - 1); // top row (y = 0)
  constexpr int kBand = 32;
  const int nBands = (height + kBand - 1) / kBand;
  if (depthMode || wantIds)
  {
    // Per-pixel ids: an int64 array in the colour image's (VTK) row order, written in place
    // (catar::RasterId is long long, as vtkTypeInt64; a platform where they differ gets a copy).
    vtkNew<vtkTypeInt64Array> visibleTriangle;
    std::vector<catar::RasterId> idCopy;
    catar::RasterId* ids = nullptr;
    if (wantIds)
    {
      visibleTriangle->SetName("VisibleTriangle");
      visibleTriangle->SetNumberOfTuples(nPixels);
      output->GetPointData()->AddArray(visibleTriangle);
      if constexpr (std::is_same<vtkTypeInt64, catar::RasterId>::value)
      {
        ids = reinterpret_cast<catar::RasterId*>(visibleTriangle->GetPointer(0)); // same type
      }
      else
      {
        idCopy.resize(static_cast<size_t>(nPixels));
        ids = idCopy.data();
      }
    }
    // The depth buffer is scratch memory kept between executions (allocating and first touching
    // it every frame costs more than the depth test itself on some systems).
    float* depth = nullptr;
    if (depthMode)
    {
      this->DepthBuffer.resize(static_cast<size_t>(nPixels));
      depth = this->DepthBuffer.data();
    }
    DrawWithBuffers(view, triangles, textures, kBand, depth, ids);
    if (!idCopy.empty())
    {
      std::copy(idCopy.begin(), idCopy.end(), visibleTriangle->GetPointer(0));
    }
    this->NumberOfDrawnTriangles = static_cast<vtkIdType>(triangles.size());
    this->UpdateProgress(1.0);
    return 1;
  }
  vtkSMPTools::For(0, nBands, 1, [&](vtkIdType b0, vtkIdType b1) {
    for (vtkIdType b = b0; b < b1; ++b)
    {
      const catar::PixelRect band{ 0, static_cast<int>(b * kBand), width,
        static_cast<int>(std::min<vtkIdType>(height, (b + 1) * kBand)) };
      for (const Triangle& t : triangles)
      {
        if (t.YMax < band.y0 - 0.5 || t.YMin > band.y1 - 0.5)
        {
          continue;
        }
        catar::rasterizeTriangle(view, t.V[0], t.V[1], t.V[2], band, nullptr,
          t.Texture >= 0 ? &textures[t.Texture] : nullptr);
      }
    }
  });
  this->NumberOfDrawnTriangles = static_cast<vtkIdType>(triangles.size());
  this->UpdateProgress(1.0);
  return 1;
}

const char* vtkCatadioptricCompositor::GetVisibilityAsString()
{
  return this->Visibility == DEPTH_BUFFER ? "DepthBuffer" : "Painter";
}

void vtkCatadioptricCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Color: " << this->Color[0] << ", " << this->Color[1] << ", " << this->Color[2]
     << "\n";
  os << indent << "Opacity: " << this->Opacity << "\n";
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)")
     << "\n";
  os << indent << "BackgroundColor: " << this->BackgroundColor[0] << ", "
     << this->BackgroundColor[1] << ", " << this->BackgroundColor[2] << ", "
     << this->BackgroundColor[3] << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "RepeatTextures: " << (this->RepeatTextures ? "On" : "Off") << "\n";
  os << indent << "Visibility: " << this->GetVisibilityAsString() << "\n";
  os << indent << "OutputVisibleTriangle: " << (this->OutputVisibleTriangle ? "On" : "Off") << "\n";
}
