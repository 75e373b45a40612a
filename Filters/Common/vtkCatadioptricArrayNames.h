/**
 * @file   vtkCatadioptricArrayNames.h
 * @brief  the names of the arrays the pipeline's stages exchange, in one place
 *
 * The projection writes them, the lighting, painter sort, compositor and ray tracer read them;
 * the field-data arrays of the camera are vtkCatadioptricCamera's own (WriteToFieldData).
 * C++ only (not wrapped); Python and ParaView users see the strings.
 */
#ifndef vtkCatadioptricArrayNames_h
#define vtkCatadioptricArrayNames_h

namespace vtkCatadioptricArrayNames
{
/// Point data, 2 doubles: the pixel (x right, y down) of each point's reflection.
constexpr const char* ImageCoordinates = "ImageCoordinates";
/// Point data, 3 doubles: the reflection point on the mirror, in world coordinates.
constexpr const char* MirrorPoint = "MirrorPoint";
/// Point data, double: the length of the reflected path, camera -> mirror -> point.
constexpr const char* PathLength = "PathLength";
/// Point data, unsigned char: vtkCatadioptricCamera::StatusCodes of each point's projection.
constexpr const char* ProjectionStatus = "ProjectionStatus";
/// Point and cell data, unsigned char: 1 where the projection is drawable.
constexpr const char* Visible = "Visible";
/// Cell data, double: the painter's distance, from each cell's centroid to its reflection point.
constexpr const char* CentroidDepth = "CentroidDepth";
/// Cell data, id: the input cell each output cell came from (painter sort).
constexpr const char* OriginalCellId = "OriginalCellId";
/// Point or cell data, RGBA unsigned char: the colours drawn (lit or given).
constexpr const char* Colors = "Colors";
/// Point data, 2 or more components: texture coordinates (also read: "TCoords").
constexpr const char* TextureCoordinates = "TextureCoordinates";
/// Field data, int: which texture of the compositor's port 2 a mesh uses (-1: none).
constexpr const char* TextureIndex = "TextureIndex";
/// Point data, integer: which of the mesh's "Materials" each point has (vtkCatadioptricLighting).
constexpr const char* MaterialIndex = "MaterialIndex";
/// Field data, 14 doubles a material (vtkCatadioptricLightingSupport::ReadMaterials).
constexpr const char* Materials = "Materials";
/// Field data, 23 doubles: the lighting that vtkCatadioptricLighting leaves in its output (its
/// WriteToFieldData), read by vtkCatadioptricRayTracer.
constexpr const char* LightingSettings = "LightingSettings";
/// Field data, 22 doubles a light: the lights of that record.
constexpr const char* LightingLights = "LightingLights";
/// Field data, one string: the base colour array of that record ("" for none).
constexpr const char* LightingColorArray = "LightingColorArray";
/// Point or cell data: the input's base colours named "Colors", kept by vtkCatadioptricLighting
/// where its lit Colors replace them.
constexpr const char* BaseColors = "BaseColors";
/// Image point data, RGBA unsigned char: the images made.
constexpr const char* RGBA = "RGBA";
/// Image point data, int64: the triangle drawn at each pixel (-1: none).
constexpr const char* VisibleTriangle = "VisibleTriangle";
/// Cell data, int: which part of the rig each cell of vtkCatadioptricRigSource draws
/// (vtkCatadioptricRigSource::RigParts).
constexpr const char* RigPart = "RigPart";
}

#endif
