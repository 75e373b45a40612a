/**
 * @class   vtkCatadioptricTriangleBins
 * @brief   the compositor's triangles read from its meshes into catar::TriangleBins
 *
 * Not a vtkObject (C++ only, not wrapped). vtkCatadioptricCompositor draws the triangles (fans of
 * the visible polygons) of its meshes binned into image bands by catar::TriangleBins
 * (Module/Raster/TriangleBins.h, which says what is kept and why). This class is its VTK reader:
 * Build() reads the meshes' points and polygons in parallel with typed access (no virtual call
 * per value for the array types the pipeline makes; any other type is read through vtkDataArray,
 * with the same values), then lets catar::TriangleBins make, order and bin the triangles. Colours
 * are ColorArrayName's array (vtkCatadioptricColorArray), or the solid colour, times Opacity.
 *
 * Build() makes at most two parallel loops (three when the order is not cell order), and reads
 * small meshes in the calling thread: waking the pool's threads costs more than reading them.
 */
#ifndef vtkCatadioptricTriangleBins_h
#define vtkCatadioptricTriangleBins_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "TriangleBins.h"                  // for catar::TriangleBins
#include "vtkCatadioptricColorArray.h"     // for vtkCatadioptricColorArray

#include <optional> // for std::optional
#include <string>   // for std::string
#include <vector>   // for std::vector

class vtkCellArray;
class vtkDataArray;
class vtkPolyData;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricTriangleBins : public catar::TriangleBins
{
public:
  /// One mesh, its arrays found and checked by the caller.
  struct Mesh
  {
    vtkPolyData* Data = nullptr;
    vtkDataArray* Pixels = nullptr;        ///< point data ImageCoordinates (2 components)
    vtkDataArray* Visible = nullptr;       ///< cell data Visible (0: skipped)
    vtkDataArray* CentroidDepth = nullptr; ///< cell data CentroidDepth (merging meshes)
    vtkDataArray* PathLength = nullptr;    ///< point data depth (depth buffer), else null
    vtkDataArray* OriginalIds = nullptr;   ///< cell data OriginalCellId (ids), or null
    vtkDataArray* TCoords = nullptr;       ///< texture coordinates (>= 2 components), or null
    int Texture = -1;                      ///< texture index (with TCoords), else -1
    bool TextureOpaque = true;             ///< the texture has no alpha below 255
    int Key = 0;                           ///< mesh index in the ids (id = Key * 2^32 + cell)
  };

  /// How the meshes are drawn, and the colour array to read.
  struct Options : catar::TriangleBins::Options
  {
    const char* ColorArrayName = nullptr; ///< point or cell colour array (may be null)
  };

  /// Gathers, orders and bins the triangles of `meshes`. False with `error` set when they do not
  /// fit the 32-bit indices.
  bool Build(const std::vector<Mesh>& meshes, const Options& options, std::string& error);

private:
  // What reading a mesh needs besides catar::TriangleBins::MeshInfo.
  struct Source
  {
    const Mesh* Input = nullptr;
    std::optional<vtkCatadioptricColorArray> Colour; // the colour array, when there is one
    vtkCellArray* Polys = nullptr;
    vtkIdType FirstCellId = 0; // cell id of the first polygon (after verts and lines)
  };

  void ReadPoints(const Chunk& chunk);
  void ReadCells(Chunk& chunk);

  std::vector<Source> Readers; // per mesh
};

#endif
