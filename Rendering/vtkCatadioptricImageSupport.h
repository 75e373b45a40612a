/**
 * @class   vtkCatadioptricImageSupport
 * @brief   input handling shared by the image sinks (compositor and reference ray tracer)
 *
 * Not a vtkObject (C++ only, not wrapped). Both sinks take the same inputs (port 0 a camera frame,
 * port 2 textures, meshes with texture coordinates) and must read them the same way, so that
 * their images compare pixel by pixel.
 */
#ifndef vtkCatadioptricImageSupport_h
#define vtkCatadioptricImageSupport_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "Rasterizer.h"                    // for catar::TextureView
#include "VideoIO.h"                       // for catar::Frame
#include "vtkType.h"                       // for vtkIdType

#include <initializer_list> // for std::initializer_list
#include <string>           // for std::string
#include <vector>           // for std::vector

class vtkDataArray;
class vtkImageData;
class vtkInformationVector;
class vtkPolyData;
template<class T>
class vtkSmartPointer;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricImageSupport
{
public:
  /// RequestUpdateExtent of a sink: asks for the whole extent of every input on `ports`.
  static void RequestWholeExtents(
    vtkInformationVector** inputVector, std::initializer_list<int> ports);

  /// Fills `n` RGBA pixels from a frame of `components` (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA)
  /// unsigned char values per pixel, in parallel.
  static void CopyFrame(
    const unsigned char* frame, int components, vtkIdType n, unsigned char* out);

  /// Fills `n` RGBA pixels with a colour given in [0, 1] (clamped), in parallel.
  static void FillColor(const double rgba[4], vtkIdType n, unsigned char* out);

  /// `output` as a width x height RGBA unsigned char image (scalars named RGBA; reused from the
  /// last run when no one else holds them); returns its bytes.
  static unsigned char* AllocateRGBA(vtkImageData* output, int width, int height);

  ///@{
  /// CopyFrame and FillColor for the pixels [begin, end) only, in the calling thread: for a sink
  /// that writes each part of its image, background first, in a parallel task of its own.
  static void CopyFramePixels(
    const unsigned char* frame, int components, vtkIdType begin, vtkIdType end, unsigned char* out);
  static void FillColorPixels(
    const double rgba[4], vtkIdType begin, vtkIdType end, unsigned char* out);
  ///@}

  /// Views of the textures connected to `textures` (2D unsigned char images of 1, 3 or 4
  /// components, row 0 at the bottom). False with `error` set when one is not such an image.
  static bool ReadTextures(vtkInformationVector* textures, bool repeat,
    std::vector<catar::TextureView>& views, std::string& error);

  /// Reads an image file (PNG, JPEG, TIFF, BMP, PNM, Radiance HDR, ...: what OpenCV's imread
  /// reads) into a 2D image of 1 to 4 components, row 0 at the bottom as VTK keeps it, RGB(A)
  /// order. 8-bit images give unsigned char scalars, 16-bit unsigned short, HDR float.
  /// Truncated or corrupt files are refused with a sentence in `error` (null returned): they go
  /// through a decoder that reports errors, not VTK's readers, some of which crash on them.
  /// Images over catar::kMaxImagePixels (CameraModel.h) are refused too.
  static vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path, std::string& error);

  /// An RGBA image (VTK's rows, the bottom one first) as a catar::Frame (the top row first, as
  /// files and OpenCV have them), and back (the image resized to the frame, 4 components).
  static catar::Frame ToFrame(vtkImageData* image);
  static void FromFrame(const catar::Frame& frame, vtkImageData* image);

  /// The texture a mesh names in its field data array TextureIndex (one integer; negative:
  /// untextured), 0 without the array. False with a sentence in `error` when the array is empty
  /// or its value is not an integer in the int range (NaN, 1e30, 2.5).
  static bool TextureIndex(vtkPolyData* mesh, int& index, std::string& error);

  /// The texture coordinates of a mesh: its active TCoords, else an array "TCoords" or
  /// "TextureCoordinates", with at least 2 components; null without.
  static vtkDataArray* TextureCoordinates(vtkPolyData* mesh);
};

#endif
