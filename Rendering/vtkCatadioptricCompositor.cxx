#include "vtkCatadioptricCompositor.h"

#include "CameraModel.h"
#include "EdgeSamples.h"
#include "Rasterizer.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricColorArray.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricTriangleBins.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricCompositor);

namespace
{
// `kept` with n tuples of nc components: reused when nothing but `kept` holds it (the pipeline
// removed it from the last output and no one downstream kept it), else a new array. A new
// 1328x1048 id image is 11 MB that the system must map and zero again at first touch, every
// frame.
template<typename ArrayT>
ArrayT* KeptArray(vtkSmartPointer<ArrayT>& kept, int nc, vtkIdType n)
{
  if (!kept || kept->GetReferenceCount() > 1)
  {
    kept = vtkSmartPointer<ArrayT>::New();
  }
  kept->SetNumberOfComponents(nc);
  vtkCatadioptricAllocation::Tuples(kept, n);
  return kept;
}

// The id buffer (VTK row order, width x height values) addressed top row first, as the rasteriser
// addresses pixels.
catar::IdView TopRowFirst(catar::RasterId* ids, int width, int height)
{
  catar::IdView view;
  view.data = ids + static_cast<std::ptrdiff_t>(width) * (height - 1); // top row: the last VTK row
  view.width = width;
  view.height = height;
  view.rowStride = -static_cast<std::ptrdiff_t>(width);
  return view;
}

// Draws the binned triangles onto view, band by band in parallel, each band its own triangles in
// their order, so the drawing order holds within every pixel. Each band first writes its rows of
// the background -- background(begin, end) for the pixels [begin, end) of the output, VTK row
// order -- which saves a parallel loop of its own and draws onto rows still in the cache. depth
// (width x height floats, top row first) and ids (the output array, VTK row order) may be null;
// each band initialises its own rows of both. With a depth test the opaque triangles (first in
// the bins' order) write depth and the others only test it; without (depthTest false: painter
// order with the depths kept for the PathLength output) every triangle writes its depth.
template<typename Background>
void DrawBands(const catar::ImageView& view, const catar::TriangleBins& bins,
  const std::vector<catar::TextureView>& textures, const Background& background, float* depth,
  bool depthTest, catar::RasterId* ids)
{
  const int width = view.width;
  const int height = view.height;
  const std::ptrdiff_t w = width;
  catar::DepthView write;
  if (depth)
  {
    write.data = depth;
    write.width = width;
    write.height = height;
    write.rowStride = w;
    write.test = depthTest;
  }
  catar::DepthView test = write;
  test.write = false;
  const catar::IdView idView = ids ? TopRowFirst(ids, width, height) : catar::IdView();
  // One band per task, heaviest first: the object often covers only a few bands.
  vtkCatadioptricParallel::ForEachIndex(0, bins.GetNumberOfBands(), [&](vtkIdType i) {
    const int b = bins.GetBandByLoad(static_cast<int>(i));
    const catar::PixelRect band = bins.GetBand(b);
    background(w * (height - band.y1), w * (height - band.y0)); // rows y1 - 1 ... y0
    for (int y = band.y0; y < band.y1; ++y)
    {
      if (depth)
      {
        std::fill(write.at(0, y), write.at(0, y) + width, std::numeric_limits<float>::infinity());
      }
      if (ids)
      {
        std::fill(idView.at(0, y), idView.at(0, y) + width, catar::RasterId(-1));
      }
    }
    catar::SnappedTriangle t;
    catar::TriangleBins::Info info;
    bins.ForEachTriangle(b, [&](std::uint32_t ref) {
      bins.Get(ref, t, info);
      catar::rasterizeSnappedTriangle(view, t, band,
        depth ? (info.Opaque || !depthTest ? &write : &test) : nullptr,
        info.Texture >= 0 ? &textures[info.Texture] : nullptr, ids ? &idView : nullptr, info.Id);
    });
  });
}

// The PathLength output: the depth buffer's rows (top first) in VTK's row order; a pixel never
// drawn (infinite depth) is NaN.
vtkSmartPointer<vtkFloatArray> PathLengthImage(const float* depth, int width, int height)
{
  const vtkIdType nPixels = static_cast<vtkIdType>(width) * height;
  auto pathLength = vtkSmartPointer<vtkFloatArray>::New();
  pathLength->SetName(vtkCatadioptricArrayNames::PathLength);
  vtkCatadioptricAllocation::Tuples(pathLength, nPixels);
  float* to = pathLength->GetPointer(0);
  vtkCatadioptricParallel::For(0, height, 64, [&](vtkIdType y0, vtkIdType y1) {
    for (vtkIdType y = y0; y < y1; ++y)
    {
      const float* row = depth + y * width;
      float* outRow = to + (height - 1 - y) * width;
      for (int x = 0; x < width; ++x)
      {
        outRow[x] = std::isinf(row[x]) ? std::numeric_limits<float>::quiet_NaN() : row[x];
      }
    }
  });
  return pathLength;
}

// The meshes to draw, their arrays checked (PathLength when wantPathLength; OriginalCellId when
// wantIds; the colour array; the texture they name). False, with an error, when one lacks what it
// needs.
bool CollectMeshes(vtkObject* self, vtkInformationVector* meshInputs,
  const std::vector<catar::TextureView>& textures, const std::vector<char>& opaqueTexture,
  const char* colorArrayName, const float solid[4], bool wantPathLength, bool wantIds,
  std::vector<vtkCatadioptricTriangleBins::Mesh>& meshes)
{
  for (int m = 0; m < meshInputs->GetNumberOfInformationObjects(); ++m)
  {
    vtkPolyData* mesh = vtkPolyData::GetData(meshInputs, m);
    if (!mesh || mesh->GetNumberOfPolys() == 0)
    {
      continue;
    }
    vtkCatadioptricTriangleBins::Mesh in;
    in.Data = mesh;
    in.Key = m;
    in.Pixels = mesh->GetPointData()->GetArray(vtkCatadioptricArrayNames::ImageCoordinates);
    in.Visible = mesh->GetCellData()->GetArray(vtkCatadioptricArrayNames::Visible);
    in.CentroidDepth = mesh->GetCellData()->GetArray(vtkCatadioptricArrayNames::CentroidDepth);
    if (!in.Pixels || in.Pixels->GetNumberOfComponents() != 2 || !in.Visible || !in.CentroidDepth)
    {
      vtkErrorWithObjectMacro(self,
        "Mesh " << m
                << " lacks ImageCoordinates/Visible/CentroidDepth: run "
                   "vtkCatadioptricProjection first.");
      return false;
    }
    // DEPTH_BUFFER and OutputPathLength: the per-vertex depth.
    if (wantPathLength)
    {
      in.PathLength = mesh->GetPointData()->GetArray(vtkCatadioptricArrayNames::PathLength);
      if (!in.PathLength || in.PathLength->GetNumberOfComponents() != 1 ||
        in.PathLength->GetNumberOfTuples() != mesh->GetNumberOfPoints())
      {
        vtkErrorWithObjectMacro(self,
          "Mesh " << m
                  << " has no PathLength point array (1 component, one value per "
                     "point), which Visibility DEPTH_BUFFER and OutputPathLength "
                     "need: run vtkCatadioptricProjection first.");
        return false;
      }
    }
    // OutputVisibleTriangle: the cells' original ids, when the mesh has them.
    if (wantIds)
    {
      in.OriginalIds = mesh->GetCellData()->GetArray(vtkCatadioptricArrayNames::OriginalCellId);
      if (in.OriginalIds &&
        (in.OriginalIds->GetNumberOfComponents() != 1 ||
          in.OriginalIds->GetNumberOfTuples() != mesh->GetNumberOfCells()))
      {
        vtkErrorWithObjectMacro(self,
          "Mesh " << m
                  << ": the cell array OriginalCellId must have 1 component and one "
                     "value per cell.");
        return false;
      }
    }
    const vtkCatadioptricColorArray color(mesh, colorArrayName, solid);
    if (color.HasArray() && color.GetNumberOfComponents() < 1)
    {
      vtkErrorWithObjectMacro(self, "Colour array " << colorArrayName << " has no components.");
      return false;
    }
    // Texture: the one the mesh names in field data (TextureIndex), else the first, when the mesh
    // has texture coordinates.
    // A negative TextureIndex leaves the mesh untextured.
    in.TCoords = textures.empty() ? nullptr : vtkCatadioptricImageSupport::TextureCoordinates(mesh);
    if (in.TCoords)
    {
      in.Texture = 0;
      std::string textureError;
      if (!vtkCatadioptricImageSupport::TextureIndex(mesh, in.Texture, textureError))
      {
        vtkErrorWithObjectMacro(self, "Mesh " << m << ": " << textureError);
        return false;
      }
      if (in.Texture < 0)
      {
        in.TCoords = nullptr;
        in.Texture = -1;
      }
      else if (in.Texture >= static_cast<int>(textures.size()))
      {
        vtkErrorWithObjectMacro(self,
          "Mesh " << m << " asks for texture " << in.Texture << " but " << textures.size()
                  << " are connected.");
        return false;
      }
      else
      {
        in.TextureOpaque = opaqueTexture[in.Texture] != 0;
      }
    }
    meshes.push_back(in);
  }
  return true;
}

// The VisibleTriangle output (nPixels values, kept from the last execution when no one else holds
// it), added to output, and where the rasteriser writes its ids: the array itself, or idCopy
// where catar::RasterId is not vtkTypeInt64.
catar::RasterId* IdImage(vtkSmartPointer<vtkTypeInt64Array>& kept, vtkImageData* output,
  vtkIdType nPixels, vtkTypeInt64Array*& visibleTriangle, std::vector<catar::RasterId>& idCopy)
{
  visibleTriangle = KeptArray(kept, 1, nPixels);
  visibleTriangle->SetName(vtkCatadioptricArrayNames::VisibleTriangle);
  output->GetPointData()->AddArray(visibleTriangle);
  if constexpr (std::is_same<vtkTypeInt64, catar::RasterId>::value)
  {
    return reinterpret_cast<catar::RasterId*>(visibleTriangle->GetPointer(0)); // same type
  }
  else
  {
    idCopy.resize(static_cast<size_t>(nPixels));
    return idCopy.data();
  }
}

// Antialias: redraws the edge pixels of the drawn image from samples (ids: the id buffer, VTK row
// order), each sample's background from the frame (frameComponents a pixel) or the colour.
// Returns the number of edge pixels.
vtkIdType DrawEdges(catar::EdgeSamples& edges, const catar::TriangleBins& bins,
  const catar::ImageView& view, catar::RasterId* ids,
  const std::vector<catar::TextureView>& textures, const std::vector<char>& opaqueTexture,
  const unsigned char* frameData, int frameComponents, const double* color, bool depthTest)
{
  const int width = view.width;
  const int height = view.height;
  edges.Draw(
    view, TopRowFirst(ids, width, height), bins, textures, opaqueTexture,
    [&](int x, int y, std::uint8_t rgba[4]) {
      if (frameData)
      {
        const vtkIdType i = static_cast<vtkIdType>(height - 1 - y) * width + x; // VTK order
        vtkCatadioptricImageSupport::CopyFramePixels(
          frameData + i * frameComponents, frameComponents, 0, 1, rgba);
      }
      else
      {
        vtkCatadioptricImageSupport::FillColorPixels(color, 0, 1, rgba);
      }
    },
    depthTest, vtkCatadioptricParallel::GetNumberOfThreads());
  return edges.GetNumberOfEdgePixels();
}

// Whether each texture is opaque (catar::IsOpaque), when needed; all are taken as opaque when not.
std::vector<char> OpaqueTextures(const std::vector<catar::TextureView>& textures, bool needed)
{
  std::vector<char> opaque(textures.size(), 1);
  for (std::size_t t = 0; needed && t < textures.size(); ++t)
  {
    opaque[t] = catar::IsOpaque(textures[t]);
  }
  return opaque;
}
} // namespace

vtkCatadioptricCompositor::vtkCatadioptricCompositor()
  : Bins(new vtkCatadioptricTriangleBins)
  , Edges(new catar::EdgeSamples)
{
}

vtkCatadioptricCompositor::~vtkCatadioptricCompositor() = default;

void vtkCatadioptricCompositor::ImageSizeWithoutFrame(
  vtkInformationVector** inputVector, int size[2])
{
  // A wrong guess would make ParaView's image views refuse the output.
  size[0] = this->ImageSize[0];
  size[1] = this->ImageSize[1];
  for (int m = 0;
       (size[0] <= 0 || size[1] <= 0) && m < inputVector[1]->GetNumberOfInformationObjects(); ++m)
  {
    vtkInformation* meshInfo = inputVector[1]->GetInformationObject(m);
    if (meshInfo->Has(vtkCatadioptricCamera::IMAGE_SIZE()))
    {
      meshInfo->Get(vtkCatadioptricCamera::IMAGE_SIZE(), size);
    }
  }
  size[0] = size[0] > 0 ? size[0] : std::max(1, this->LastSize[0]);
  size[1] = size[1] > 0 ? size[1] : std::max(1, this->LastSize[1]);
}

bool vtkCatadioptricCompositor::MeshImageSize(
  vtkInformationVector* meshInputs, int& width, int& height)
{
  vtkNew<vtkCatadioptricCamera> camera;
  for (int m = 0; m < meshInputs->GetNumberOfInformationObjects(); ++m)
  {
    vtkPolyData* mesh = vtkPolyData::GetData(meshInputs, m);
    if (!mesh)
    {
      continue;
    }
    std::string meshError;
    if (!vtkCatadioptricMeshCheck::Check(mesh, meshError))
    {
      vtkErrorMacro("Mesh " << m << ": " << meshError);
      return false;
    }
    if (mesh->GetNumberOfPoints() == 0)
    {
      continue;
    }
    if (!camera->ReadFromFieldData(mesh->GetFieldData()))
    {
      vtkErrorMacro("Mesh " << m << ": " << camera->GetLastError());
      return false;
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
      return false;
    }
  }
  return true;
}

int vtkCatadioptricCompositor::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Out of memory (a mesh or an image too large for the memory left): the filter's error.
  return vtkCatadioptricAllocation::Guard(
    this, [&] { return this->Execute(inputVector, outputVector); },
    [&] {
      return "drawing " + vtkCatadioptricAllocation::DescribeInput(inputVector[1]) + " into " +
        vtkCatadioptricAllocation::DescribeOutputImage(outputVector);
    });
}

int vtkCatadioptricCompositor::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkImageData* frame = vtkImageData::GetData(inputVector[0]);
  const bool depthMode = this->Visibility == DEPTH_BUFFER;
  const bool wantIds = this->OutputVisibleTriangle;
  const bool wantDepths = this->OutputPathLength;
  this->NumberOfDrawnTriangles = 0;
  this->NumberOfSkippedTriangles = 0;
  this->NumberOfEdgePixels = 0;
  const int samples = this->Antialias ? this->AntialiasSamples : 1;

  // Image size: from the meshes' cameras, which must agree with each other and with the frame.
  int width = 0;
  int height = 0;
  if (!this->MeshImageSize(inputVector[1], width, height))
  {
    return 0;
  }
  const int frameComponents = this->CheckFrame(frame, width, height);
  if (frameComponents < 0)
  {
    return 0;
  }
  if (frame)
  {
    width = frame->GetDimensions()[0];
    height = frame->GetDimensions()[1];
  }
  if (!this->ResolveImageSize(frame != nullptr, width, height))
  {
    return 0;
  }
  this->LastSize[0] = width;
  this->LastSize[1] = height;
  unsigned char* out = vtkCatadioptricImageSupport::AllocateRGBA(output, width, height);
  const vtkIdType nPixels = static_cast<vtkIdType>(width) * height;

  // Background, written band by band with the triangles: the frame (grey and RGB widened to
  // RGBA), or a colour.
  const unsigned char* frameData = frame
    ? static_cast<const unsigned char*>(frame->GetPointData()->GetScalars()->GetVoidPointer(0))
    : nullptr;
  const auto background = [&](vtkIdType begin, vtkIdType end) {
    if (frameData)
    {
      vtkCatadioptricImageSupport::CopyFramePixels(frameData, frameComponents, begin, end, out);
    }
    else
    {
      vtkCatadioptricImageSupport::FillColorPixels(this->BackgroundColor, begin, end, out);
    }
  };
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
  // DEPTH_BUFFER and anti-aliasing: an RGBA texture is opaque when every alpha byte is 255.
  const std::vector<char> opaqueTexture = OpaqueTextures(textures, depthMode || samples > 1);

  // The meshes' arrays, checked here; the bins read them (in parallel, with typed access).
  std::vector<vtkCatadioptricTriangleBins::Mesh> meshes;
  const float solid[4] = { static_cast<float>(this->Color[0]), static_cast<float>(this->Color[1]),
    static_cast<float>(this->Color[2]), 1.0f };
  if (!CollectMeshes(this, inputVector[1], textures, opaqueTexture, this->ColorArrayName, solid,
        depthMode || wantDepths, wantIds, meshes))
  {
    return 0;
  }

  // The triangles, in drawing order, binned into the bands they meet: painter order (cell
  // order, one far-to-near order by CentroidDepth across meshes, each mesh keeping its own order
  // among equal depths), and with a depth buffer the opaque triangles first.
  vtkCatadioptricTriangleBins::Options options;
  options.Width = width;
  options.Height = height;
  options.ColorArrayName = this->ColorArrayName;
  std::copy(solid, solid + 4, options.Solid);
  options.Opacity = static_cast<float>(this->Opacity);
  options.MergeByDepth = inputVector[1]->GetNumberOfInformationObjects() > 1;
  options.DepthBuffer = depthMode;
  options.Depths = depthMode || wantDepths;
  options.Ids = wantIds || samples > 1; // edges are found on the ids
  options.Samples = samples;
  std::string binError;
  if (!this->Bins->Build(meshes, options, binError))
  {
    vtkErrorMacro(<< binError);
    return 0;
  }
  this->NumberOfDrawnTriangles = this->Bins->GetNumberOfTriangles();
  this->NumberOfSkippedTriangles = this->Bins->GetNumberOfSkippedTriangles();
  this->UpdateProgress(0.4);

  // Rasterise the bands in parallel.
  catar::ImageView view;
  view.width = width;
  view.height = height;
  view.rowStride = -4 * static_cast<std::ptrdiff_t>(width);
  view.data = out + 4 * static_cast<std::ptrdiff_t>(width) * (height - 1); // top row (y = 0)
  // Per-pixel ids: an int64 array in the colour image's (VTK) row order, written in place
  // (catar::RasterId is long long, as vtkTypeInt64; a platform where they differ gets a copy).
  std::vector<catar::RasterId> idCopy;
  vtkTypeInt64Array* visibleTriangle = nullptr;
  catar::RasterId* ids =
    wantIds ? IdImage(this->OutputIds, output, nPixels, visibleTriangle, idCopy) : nullptr;
  // The depth buffer is scratch memory kept between executions (allocating and first touching
  // it every frame costs more than the depth test itself on some systems).
  float* depth = nullptr;
  if (depthMode || wantDepths)
  {
    this->DepthBuffer.resize(static_cast<size_t>(nPixels));
    depth = this->DepthBuffer.data();
  }
  if (samples > 1 && !ids)
  {
    this->EdgeIds.resize(static_cast<size_t>(nPixels));
    ids = this->EdgeIds.data();
  }
  DrawBands(view, *this->Bins, textures, background, depth, depthMode, ids);
  if (samples > 1)
  {
    this->NumberOfEdgePixels = DrawEdges(*this->Edges, *this->Bins, view, ids, textures,
      opaqueTexture, frameData, frameComponents, this->BackgroundColor, depthMode);
  }
  if (!idCopy.empty())
  {
    std::copy(idCopy.begin(), idCopy.end(), visibleTriangle->GetPointer(0));
  }
  if (wantDepths)
  {
    output->GetPointData()->AddArray(PathLengthImage(depth, width, height));
  }
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
  os << indent << "Visibility: " << this->GetVisibilityAsString() << "\n";
  os << indent << "Antialias: " << this->Antialias << " (" << this->AntialiasSamples << " x "
     << this->AntialiasSamples << " samples)\n";
}
