#include "vtkCatadioptricTriangleBins.h"

#include "vtkArrayDispatch.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace
{
// Below this many points and polygons they are read in the calling thread: reading them takes
// ~1.5 ns each, and waking the pool's threads costs ~10 us plus the other cores' cache misses on
// what this one wrote.
constexpr vtkIdType kSerialReading = 16384;

// Typed access: the array types the pipeline makes are read without a virtual call per value
// (ImageCoordinates, PathLength, CentroidDepth: double; texture coordinates: float or double;
// Visible: unsigned char; OriginalCellId: vtkIdType); any other array is read through
// vtkDataArray's virtual API. Both give the values vtkDataArray::GetComponent gives.
using FastArrays = vtkTypeList::Unique<
  vtkTypeList::Create<vtkAOSDataArrayTemplate<double>, vtkAOSDataArrayTemplate<float>,
    vtkAOSDataArrayTemplate<unsigned char>, vtkAOSDataArrayTemplate<vtkIdType>>>::Result;
using FastDispatch = vtkArrayDispatch::DispatchByArray<FastArrays>;

// Calls worker(range, components) with a value range of `array` (range[i * components + k] is
// component k of tuple i, converted to double as GetComponent converts it).
template<typename Worker>
void WithValues(vtkDataArray* array, Worker&& worker)
{
  auto run = [&](auto* typed) {
    worker(vtk::DataArrayValueRange(typed), typed->GetNumberOfComponents());
  };
  if (!FastDispatch::Execute(array, run))
  {
    run(array);
  }
}

// The value of an attribute as the compositor has always converted it: to double (as
// GetComponent returns it), then to float.
template<typename T>
float ToFloat(T value)
{
  return static_cast<float>(static_cast<double>(value));
}

bool Finite(const float c[4])
{
  return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(c[3]);
}

// The unsigned char colour array whose bytes a PointBytes mesh keeps with its points
// (vtkCatadioptricLighting's "Colors"), else null.
vtkUnsignedCharArray* ByteColours(const vtkCatadioptricColorArray& colour)
{
  auto* bytes = vtkUnsignedCharArray::FastDownCast(colour.GetArray());
  return bytes && bytes->GetNumberOfComponents() >= 3 ? bytes : nullptr;
}

} // namespace

bool vtkCatadioptricTriangleBins::Build(
  const std::vector<Mesh>& meshes, const Options& options, std::string& error)
{
  this->Start(options, &vtkCatadioptricParallel::GetNumberOfThreads);
  this->Readers.clear();
  this->Readers.reserve(meshes.size());
  vtkIdType nPoints = 0, nCells = 0;
  for (const Mesh& in : meshes)
  {
    Source source;
    source.Input = &in;
    source.Colour.emplace(in.Data, options.ColorArrayName, options.Solid);
    source.Polys = in.Data->GetPolys();
    source.FirstCellId = in.Data->GetNumberOfVerts() + in.Data->GetNumberOfLines();
    MeshInfo m;
    m.Colours = !source.Colour->HasArray() ? ColourSource::Solid
      : !source.Colour->IsPerPoint()       ? ColourSource::Cell
      : ByteColours(*source.Colour)        ? ColourSource::PointBytes
                                           : ColourSource::PointFloats;
    m.Texture = in.TCoords ? in.Texture : -1;
    m.TextureOpaque = in.TextureOpaque;
    const vtkIdType points = in.Data->GetNumberOfPoints();
    const vtkIdType cells = source.Polys->GetNumberOfCells();
    this->AddMesh(m, points, cells);
    this->Readers.push_back(source);
    nPoints += points;
    nCells += cells;
  }
  if (!this->Allocate(error))
  {
    return false;
  }

  // Points and polygons, one task per chunk: the two kinds are independent.
  const vtkIdType nPointTasks = static_cast<vtkIdType>(this->PointChunks.size());
  const vtkIdType nTasks = nPointTasks + static_cast<vtkIdType>(this->CellChunks.size());
  const vtkIdType grain = nPoints + nCells < kSerialReading ? nTasks : 1;
  vtkCatadioptricParallel::For(0, nTasks, grain, [&](vtkIdType t0, vtkIdType t1) {
    for (vtkIdType t = t0; t < t1; ++t)
    {
      if (t < nPointTasks)
      {
        this->ReadPoints(this->PointChunks[t]);
      }
      else
      {
        this->ReadCells(this->CellChunks[t - nPointTasks]);
      }
    }
  });

  // The triangles, their order and bins.
  return this->Finish(
    [this](Chunk& chunk) {
      this->Readers[chunk.Mesh].Polys->Visit([&](auto& state) {
        this->MakeTriangles(
          chunk, state.GetOffsets()->GetPointer(0), state.GetConnectivity()->GetPointer(0));
      });
    },
    error);
}

// Positions (checked and snapped), and the colours, depths and texture coordinates of the
// points [chunk.Begin, chunk.End) of a mesh.
void vtkCatadioptricTriangleBins::ReadPoints(const Chunk& chunk)
{
  const MeshInfo& m = this->Meshes[chunk.Mesh];
  const Source& r = this->Readers[chunk.Mesh];
  const Mesh& in = *r.Input;
  const vtkIdType b = chunk.Begin, e = chunk.End;
  Point* points = this->Points.data() + m.PointBase;

  // Outside the guard band (or not finite: the comparisons are false for NaN) cannot be drawn.
  WithValues(in.Pixels, [&](auto values, int nc) {
    for (vtkIdType i = b; i < e; ++i)
    {
      const double x = static_cast<double>(values[nc * i]);
      const double y = static_cast<double>(values[nc * i + 1]);
      const bool ok =
        std::fabs(x) <= catar::kRasterGuardBand && std::fabs(y) <= catar::kRasterGuardBand;
      points[i].X = ok ? catar::snapToGrid(x) : kBadPoint;
      points[i].Y = ok ? catar::snapToGrid(y) : kBadPoint;
    }
  });
  if (m.Colours == ColourSource::PointBytes)
  {
    // Finite unless Opacity is not.
    const bool finite = std::isfinite(this->Opts.Opacity);
    vtkUnsignedCharArray* array = ByteColours(*r.Colour);
    const int nc = array->GetNumberOfComponents();
    const unsigned char* bytes = array->GetPointer(0);
    for (vtkIdType i = b; i < e; ++i)
    {
      const unsigned char* c = bytes + nc * i;
      points[i].Rgba[0] = c[0];
      points[i].Rgba[1] = c[1];
      points[i].Rgba[2] = c[2];
      points[i].Rgba[3] = nc >= 4 ? c[3] : 255;
      points[i].X = finite ? points[i].X : kBadPoint;
    }
  }
  else if (m.Colours == ColourSource::PointFloats)
  {
    Rgba* colours = this->PointColours.data() + m.PointBase;
    for (vtkIdType i = b; i < e; ++i)
    {
      r.Colour->Get(i, 0, colours[i].C);
      colours[i].C[3] *= this->Opts.Opacity;
      points[i].X = Finite(colours[i].C) ? points[i].X : kBadPoint;
    }
  }
  if (this->Opts.Depths)
  {
    float* depths = this->PointDepths.data() + m.PointBase;
    WithValues(in.PathLength, [&](auto values, int nc) {
      for (vtkIdType i = b; i < e; ++i)
      {
        depths[i] = ToFloat(values[nc * i]);
        points[i].X = std::isfinite(depths[i]) ? points[i].X : kBadPoint;
      }
    });
  }
  if (m.Texture >= 0)
  {
    TCoord* tcoords = this->PointTCoords.data() + m.PointBase;
    WithValues(in.TCoords, [&](auto values, int nc) {
      for (vtkIdType i = b; i < e; ++i)
      {
        tcoords[i] = TCoord{ ToFloat(values[nc * i]), ToFloat(values[nc * i + 1]) };
        const bool finite = std::isfinite(tcoords[i].U) && std::isfinite(tcoords[i].V);
        points[i].X = finite ? points[i].X : kBadPoint;
      }
    });
  }
}

// Visibility, colour, id and depth of the polygons [chunk.Begin, chunk.End) of a mesh, and the
// number of triangles they make (chunk.Count) or skip (chunk.Skipped).
void vtkCatadioptricTriangleBins::ReadCells(Chunk& chunk)
{
  const MeshInfo& m = this->Meshes[chunk.Mesh];
  const Source& r = this->Readers[chunk.Mesh];
  const Mesh& in = *r.Input;
  const vtkIdType b = chunk.Begin, e = chunk.End;
  const vtkIdType first = r.FirstCellId; // polygon c is cell first + c
  std::uint8_t* states = this->CellStates.data() + m.CellBase;

  const std::uint8_t drawable =
    m.Colours == ColourSource::Solid && !m.SolidValid ? kNothing : kDrawable;
  WithValues(in.Visible, [&](auto values, int nc) {
    for (vtkIdType c = b; c < e; ++c)
    {
      states[c] = static_cast<double>(values[nc * (first + c)]) == 0 ? kInvisible : drawable;
    }
  });
  if (m.Colours == ColourSource::Cell)
  {
    // Unsigned char colours (vtkCatadioptricLighting's flat shading) through the byte tables,
    // others through vtkCatadioptricColorArray::Get.
    Rgba* colours = this->CellColours.data() + m.CellBase;
    vtkUnsignedCharArray* array = ByteColours(*r.Colour);
    const int nc = array ? array->GetNumberOfComponents() : 0;
    const unsigned char* bytes = array ? array->GetPointer(0) : nullptr;
    for (vtkIdType c = b; c < e; ++c)
    {
      float* rgba = colours[c].C;
      if (bytes)
      {
        const unsigned char* v = bytes + nc * (first + c);
        rgba[0] = this->Bytes[v[0]];
        rgba[1] = this->Bytes[v[1]];
        rgba[2] = this->Bytes[v[2]];
        rgba[3] = this->AlphaBytes[nc >= 4 ? v[3] : 255];
      }
      else
      {
        r.Colour->Get(0, first + c, rgba);
        rgba[3] *= this->Opts.Opacity;
      }
      if (states[c] == kDrawable && !Finite(rgba))
      {
        states[c] = kNothing;
      }
    }
  }
  if (this->Opts.Ids)
  {
    // The original id goes through double, as the compositor has always read it.
    catar::RasterId* ids = this->CellIds.data() + m.CellBase;
    const catar::RasterId key = static_cast<catar::RasterId>(in.Key) << 32;
    if (in.OriginalIds)
    {
      WithValues(in.OriginalIds, [&](auto values, int nc) {
        for (vtkIdType c = b; c < e; ++c)
        {
          ids[c] =
            key + static_cast<catar::RasterId>(static_cast<double>(values[nc * (first + c)]));
        }
      });
    }
    else
    {
      for (vtkIdType c = b; c < e; ++c)
      {
        ids[c] = key + static_cast<catar::RasterId>(first + c);
      }
    }
  }
  if (this->Opts.MergeByDepth)
  {
    double* depths = this->CellDepths.data() + m.CellBase;
    WithValues(in.CentroidDepth, [&](auto values, int nc) {
      for (vtkIdType c = b; c < e; ++c)
      {
        depths[c] = static_cast<double>(values[nc * (first + c)]);
      }
    });
  }
  // A polygon of n points makes a fan of n - 2 triangles (catar::PolygonTriangles).
  chunk.Count = 0;
  chunk.Skipped = 0;
  r.Polys->Visit([&](auto& state) {
    const auto* offsets = state.GetOffsets()->GetPointer(0);
    for (vtkIdType c = b; c < e; ++c)
    {
      const vtkIdType n = std::max<vtkIdType>(0, offsets[c + 1] - offsets[c] - 2);
      (states[c] == kInvisible ? chunk.Skipped : chunk.Count) += n;
    }
  });
}
