/**
 * @class   vtkCatadioptricCompositor
 * @brief   draws projected meshes onto the camera frame (the display step of the method)
 *
 * Input port 0 (optional): the camera frame, vtkImageData of unsigned char with 1 (grey), 3 (RGB)
 * or 4 (RGBA) components, of the camera's image size. Input port 1 (optional, repeatable): one or
 * more meshes that went through vtkCatadioptricProjection (and usually
 * vtkCatadioptricPainterSort). Output: RGBA unsigned char vtkImageData (VTK row order: row 0 is
 * the bottom of the picture, so vtkPNGWriter writes the picture OpenCV's imwrite would).
 *
 * Polygons are drawn in cell order (painter order; polygons are split into fans) by the Core CPU
 * rasteriser: a pixel is covered when its centre lies inside the projected triangle, with the
 * top-left rule on edges, vertex positions snapped to 1/256 pixel (see
 * Documentation/edges-and-rasterisation.md). Several meshes are merged into one far-to-near order
 * by their CentroidDepth. Cells whose Visible flag is 0 are skipped.
 *
 * Visibility: PAINTER (default, the paper's method) trusts that order: the last triangle drawn in
 * a pixel is the one seen. DEPTH_BUFFER adds a per-pixel z-test: each triangle carries, at its
 * vertices, the point array PathLength (mirror point to vertex, written by
 * vtkCatadioptricProjection), interpolated linearly in screen space across the projected
 * triangle (as colours are), and a pixel is drawn only where that depth is strictly smaller than
 * the stored one; interpenetrating and cyclically overlapping triangles, which no painter order
 * resolves, are then right at every pixel up to the interpolation of the depth. Opaque triangles
 * (alpha 1 at every vertex and no texture with an alpha below 255) are drawn first and write
 * their depth, so for them the draw order does not matter; semi-transparent triangles are drawn
 * after all opaque ones, in painter order, depth-tested against the opaque surfaces but without
 * writing depth, so they blend over each other in painter order and never hide anything. A mesh
 * without PathLength is an error in DEPTH_BUFFER mode.
 *
 * Visible-triangle ids: with OutputVisibleTriangle on, the output has a second point-data array,
 * "VisibleTriangle" (vtkTypeInt64Array, one value per pixel, in the same row order as the colour
 * image): -1 where no triangle was drawn, else meshIndex * 2^32 + cellId of the last triangle
 * drawn in the pixel (the visible one; with semi-transparent meshes the front-most drawn one),
 * whatever its alpha. meshIndex is the connection index on input port 1; cellId is the cell's
 * value in the cell-data array "OriginalCellId" when the mesh has one (vtkCatadioptricPainterSort
 * writes it, so ids refer to the unsorted mesh), else the cell's index in the mesh. Every triangle
 * of a polygon's fan gets the polygon's id. Decode with meshIndex = id >> 32 and cellId =
 * id & 0xFFFFFFFF (cell ids must be below 2^32).
 *
 * Colour: the array named ColorArrayName (default "Colors") if the mesh has one, as point data
 * (interpolated across each triangle: Gouraud) or cell data (flat); unsigned char arrays are read
 * as 0-255, floating point arrays as 0-1; 3 or 4 components. Otherwise the solid Color. Alpha is
 * multiplied by Opacity and composited "over" the frame.
 *
 * Textures: images on input port 2 (one or more). A mesh with texture coordinates (its active
 * TCoords, or an array TCoords / TextureCoordinates) is textured with the image its field data
 * array TextureIndex names, or the first one (a negative TextureIndex: no texture): the colour
 * above is multiplied by the bilinearly sampled texel (u, v in [0,1], (0,0) at the image's
 * bottom-left, VTK's convention).
 *
 * Anti-aliasing (Antialias, off by default): edge pixels -- silhouettes against the frame and
 * edges where one surface passes in front of another -- get the mean of AntialiasSamples x
 * AntialiasSamples samples, drawn with the same rules; interior pixels keep their centre sample
 * (see catar::EdgeSamples, Module/Raster/EdgeSamples.h).
 *
 * Without a frame the output is BackgroundColor, of ImageSize if set, else of the camera's image
 * size (from the meshes' field data).
 */
#ifndef vtkCatadioptricCompositor_h
#define vtkCatadioptricCompositor_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkCatadioptricImageSink.h"
#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <memory> // for std::unique_ptr
#include <vector> // for std::vector

class vtkCatadioptricTriangleBins;
namespace catar
{
class EdgeSamples;
}
class vtkTypeInt64Array;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricCompositor : public vtkCatadioptricImageSink
{
public:
  static vtkCatadioptricCompositor* New();
  vtkTypeMacro(vtkCatadioptricCompositor, vtkCatadioptricImageSink);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // Ports, Color, Opacity, ColorArrayName, BackgroundColor, ImageSize, RepeatTextures and
  // OutputVisibleTriangle: vtkCatadioptricImageSink.

  /// How the surface seen in each pixel is chosen (see the class comment).
  enum Visibilities
  {
    PAINTER = 0,     ///< draw in painter order; the last triangle drawn wins (default)
    DEPTH_BUFFER = 1 ///< per-pixel z-test on the interpolated PathLength
  };
  ///@{
  /// Visibility: PAINTER (default) or DEPTH_BUFFER.
  vtkSetClampMacro(Visibility, int, PAINTER, DEPTH_BUFFER);
  vtkGetMacro(Visibility, int);
  void SetVisibilityToPainter() { this->SetVisibility(PAINTER); }
  void SetVisibilityToDepthBuffer() { this->SetVisibility(DEPTH_BUFFER); }
  const char* GetVisibilityAsString();
  ///@}

  ///@{
  /// Antialias (default off): redraw the edge pixels from AntialiasSamples x AntialiasSamples
  /// samples each (2 to 4, default 4) and give them the samples' mean.
  vtkSetMacro(Antialias, bool);
  vtkGetMacro(Antialias, bool);
  vtkBooleanMacro(Antialias, bool);
  vtkSetClampMacro(AntialiasSamples, int, 2, 4);
  vtkGetMacro(AntialiasSamples, int);
  ///@}

  ///@{
  /// Statistics of the last execution: triangles sent to the rasteriser, and triangles skipped
  /// because their cell was not visible.
  vtkGetMacro(NumberOfDrawnTriangles, vtkIdType);
  vtkGetMacro(NumberOfSkippedTriangles, vtkIdType);
  /// Pixels redrawn from samples (Antialias).
  vtkGetMacro(NumberOfEdgePixels, vtkIdType);
  ///@}

protected:
  vtkCatadioptricCompositor();
  ~vtkCatadioptricCompositor() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// ImageSize, else the size the projection announced for its camera
  /// (vtkCatadioptricCamera::IMAGE_SIZE, passed down by the filters in between), else the last
  /// size.
  void ImageSizeWithoutFrame(vtkInformationVector** inputVector, int size[2]) override;
  /// The image size of the meshes' cameras (field data), which must agree; 0 x 0 without a mesh
  /// that has points. False, with an error, for a mesh that fails its checks or a disagreement.
  bool MeshImageSize(vtkInformationVector* meshInputs, int& width, int& height);

  int Visibility = PAINTER;
  bool Antialias = false;
  int AntialiasSamples = 4;
  vtkIdType NumberOfEdgePixels = 0;
  int LastSize[2] = { 0, 0 };
  vtkIdType NumberOfDrawnTriangles = 0;
  vtkIdType NumberOfSkippedTriangles = 0;
  std::vector<float> DepthBuffer; // DEPTH_BUFFER scratch, kept between executions
  // The VisibleTriangle array of the last execution, reused when no one else holds it (the
  // colour scalars are reused by vtkImageData itself).
  vtkSmartPointer<vtkTypeInt64Array> OutputIds;
  // The triangles of an execution, binned into bands; scratch kept between executions.
  std::unique_ptr<vtkCatadioptricTriangleBins> Bins;
  // Antialias: the edge pixels' samples, and the id buffer when OutputVisibleTriangle is off.
  std::unique_ptr<catar::EdgeSamples> Edges;
  std::vector<long long> EdgeIds;

private:
  // RequestData's work (RequestData reports running out of memory).
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  vtkCatadioptricCompositor(const vtkCatadioptricCompositor&) = delete;
  void operator=(const vtkCatadioptricCompositor&) = delete;
};

#endif
