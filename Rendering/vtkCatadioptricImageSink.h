/**
 * @class   vtkCatadioptricImageSink
 * @brief   what the compositor and the reference ray tracer share: ports, properties, extent
 *
 * Both make the camera's image of meshes: the frame on input port 0 (optional: without it, the
 * image is BackgroundColor at ImageSize, or the camera's size), the meshes on port 1 (several)
 * and textures on port 2 (several: unsigned char images with 1, 3 or 4 components). The output is
 * an RGBA unsigned char image of the frame's extent, and with OutputVisibleTriangle a per-pixel
 * "VisibleTriangle" array, with OutputPathLength a per-pixel "PathLength" array. Meshes without the
 * colour array ColorArrayName are drawn in Color; every colour is multiplied by Opacity; texture
 * coordinates beyond [0, 1] repeat or clamp (RepeatTextures). One set of defaults for both: Color
 * 0.8 grey, Opacity 1, "Colors", black background, textures clamped, no VisibleTriangle.
 *
 * Subclasses: vtkCatadioptricCompositor (the fast path) and vtkCatadioptricRayTracer (the exact
 * reference). They say how large the image is without a frame (ImageSizeWithoutFrame).
 */
#ifndef vtkCatadioptricImageSink_h
#define vtkCatadioptricImageSink_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class vtkImageData;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricImageSink : public vtkImageAlgorithm
{
public:
  vtkTypeMacro(vtkCatadioptricImageSink, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera frame (port 0), the meshes (port 1, several connections allowed) and the textures
  /// (port 2, several: unsigned char images with 1, 3 or 4 components).
  void SetFrameConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetFrameData(vtkDataObject* frame) { this->SetInputData(0, frame); }
  void AddMeshConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  void AddMeshData(vtkDataObject* mesh) { this->AddInputData(1, mesh); }
  void RemoveAllMeshConnections() { this->RemoveAllInputConnections(1); }
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
  /// Solid colour (RGB in [0,1]) for meshes without a colour array. Default 0.8 grey.
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);
  ///@}

  ///@{
  /// Opacity multiplied into every drawn colour, in [0,1]. Default 1.
  vtkSetClampMacro(Opacity, double, 0.0, 1.0);
  vtkGetMacro(Opacity, double);
  ///@}

  ///@{
  /// Name of the colour array (point or cell data). Default "Colors".
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  ///@}

  ///@{
  /// Background (RGBA in [0,1]) used when no frame is connected. Default opaque black.
  vtkSetVector4Macro(BackgroundColor, double);
  vtkGetVector4Macro(BackgroundColor, double);
  ///@}

  ///@{
  /// Output size when no frame is connected; (0,0) (default) means the camera's image size.
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /// Add the point-data array "VisibleTriangle" (the triangle drawn in each pixel, see the
  /// subclasses) to the output. Default off.
  vtkSetMacro(OutputVisibleTriangle, bool);
  vtkGetMacro(OutputVisibleTriangle, bool);
  vtkBooleanMacro(OutputVisibleTriangle, bool);
  ///@}

  ///@{
  /// Add the point-data array "PathLength" (float, one value per pixel, VTK row order) to the
  /// output: the length of the reflected ray from the mirror to the surface seen in the pixel
  /// (the pixel's triangle in VisibleTriangle), in scene units; NaN where no triangle is drawn.
  /// The "depth" of a catadioptric image: what a depth buffer holds. Default off.
  vtkSetMacro(OutputPathLength, bool);
  vtkGetMacro(OutputPathLength, bool);
  vtkBooleanMacro(OutputPathLength, bool);
  ///@}

protected:
  vtkCatadioptricImageSink();
  ~vtkCatadioptricImageSink() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// The frame's extent, or ImageSizeWithoutFrame's; RGBA unsigned char scalars.
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The whole frame and whole textures, whatever the output's extent.
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The image size announced when no frame is connected (RequestInformation; RequestData sets
  /// the real extent). (0, 0) announces a single pixel.
  virtual void ImageSizeWithoutFrame(vtkInformationVector** inputVector, int size[2]) = 0;

  ///@{
  /// For RequestData. CheckFrame: the frame's component count (0 when none is connected), or -1
  /// after reporting why it cannot be used (not a 2D unsigned char image of 1 to 4 components, or
  /// not width x height when width > 0). ResolveImageSize: without a frame, ImageSize (when set)
  /// becomes the size; false after reporting an ImageSize that contradicts a known size (width >
  /// 0), no size at all, or one over the limit. The output image itself is made by
  /// vtkCatadioptricImageSupport::AllocateRGBA, as the environment source's is.
  int CheckFrame(vtkImageData* frame, int width, int height);
  bool ResolveImageSize(bool haveFrame, int& width, int& height);
  ///@}

  double Color[3] = { 0.8, 0.8, 0.8 };
  double Opacity = 1.0;
  char* ColorArrayName = nullptr;
  double BackgroundColor[4] = { 0.0, 0.0, 0.0, 1.0 };
  int ImageSize[2] = { 0, 0 };
  bool RepeatTextures = false;
  bool OutputVisibleTriangle = false;
  bool OutputPathLength = false;

private:
  vtkCatadioptricImageSink(const vtkCatadioptricImageSink&) = delete;
  void operator=(const vtkCatadioptricImageSink&) = delete;
};

#endif
