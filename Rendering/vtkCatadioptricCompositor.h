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
 * top-left rule on edges, vertex positions snapped to 1/256 pixel (see README "Rasterisation").
 * Several meshes are merged into one far-to-near order by their CentroidDepth. Cells whose Visible
 * flag is 0 are skipped.
 *
 * Colour: the array named ColorArrayName (default "Colors") if the mesh has one, as point data
 * (interpolated across each triangle: Gouraud) or cell data (flat); unsigned char arrays are read
 * as 0-255, floating point arrays as 0-1; 3 or 4 components. Otherwise the solid Color. Alpha is
 * multiplied by Opacity and composited "over" the frame.
 *
 * Textures: images on input port 2 (one or more). A mesh with texture coordinates (its active
 * TCoords, or an array TCoords / TextureCoordinates) is textured with the image its field data
 * array TextureIndex names, or the first one (a negative TextureIndex: no texture): the colour above is multiplied by the bilinearly
 * sampled texel (u, v in [0,1], (0,0) at the image's bottom-left, VTK's convention).
 *
 * Without a frame the output is BackgroundColor, of ImageSize if set, else of the camera's image
 * size (from the meshes' field data).
 */
#ifndef vtkCatadioptricCompositor_h
#define vtkCatadioptricCompositor_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricCompositor : public vtkImageAlgorithm
{
public:
  static vtkCatadioptricCompositor* New();
  vtkTypeMacro(vtkCatadioptricCompositor, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera frame (port 0) and the projected meshes (port 1, several connections allowed).
  void SetFrameConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetFrameData(vtkDataObject* frame) { this->SetInputData(0, frame); }
  void AddMeshConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  void AddMeshData(vtkDataObject* mesh) { this->AddInputData(1, mesh); }
  void RemoveAllMeshConnections() { this->RemoveAllInputConnections(1); }
  /// Textures (port 2, several allowed): unsigned char images with 1, 3 or 4 components.
  void AddTextureConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(2, output); }
  void AddTextureData(vtkDataObject* texture) { this->AddInputData(2, texture); }
  void RemoveAllTextureConnections() { this->RemoveAllInputConnections(2); }
  ///@}

  ///@{
  /// Texture addressing beyond [0, 1]: repeat (on) or clamp to the edge (off, default).
  vtkSetMacro(RepeatTextures, bool);
  vtkGetMacro(RepeatTextures, bool);
  vtkBooleanMacro(RepeatTextures, bool);
  ///@}

  ///@{
  /// Solid colour (RGB in [0,1]) for meshes without a colour array.
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);
  ///@}

  ///@{
  /// Opacity multiplied into every drawn colour, in [0,1].
  vtkSetClampMacro(Opacity, double, 0.0, 1.0);
  vtkGetMacro(Opacity, double);
  ///@}

  ///@{
  /// Name of the colour array (point or cell data). Default "Colors".
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  ///@}

  ///@{
  /// Background (RGBA in [0,1]) used when no frame is connected.
  vtkSetVector4Macro(BackgroundColor, double);
  vtkGetVector4Macro(BackgroundColor, double);
  ///@}

  ///@{
  /// Output size when no frame is connected; (0,0) means the camera's image size.
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /// Statistics of the last execution: triangles sent to the rasteriser, and triangles skipped
  /// because their cell was not visible.
  vtkGetMacro(NumberOfDrawnTriangles, vtkIdType);
  vtkGetMacro(NumberOfSkippedTriangles, vtkIdType);
  ///@}

protected:
  vtkCatadioptricCompositor();
  ~vtkCatadioptricCompositor() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Color[3] = { 0.8, 0.8, 0.8 };
  double Opacity = 1.0;
  char* ColorArrayName = nullptr;
  double BackgroundColor[4] = { 0.0, 0.0, 0.0, 1.0 };
  int ImageSize[2] = { 0, 0 };
  bool RepeatTextures = false;
  int LastSize[2] = { 0, 0 };
  vtkIdType NumberOfDrawnTriangles = 0;
  vtkIdType NumberOfSkippedTriangles = 0;

private:
  vtkCatadioptricCompositor(const vtkCatadioptricCompositor&) = delete;
  void operator=(const vtkCatadioptricCompositor&) = delete;
};

#endif
