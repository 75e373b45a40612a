// CatadioptricAR Core: checks of mesh files before a reader sees them. Some of VTK's readers
// trust the counts a file's header gives (a PLY that announces 10^9 vertices in 300 bytes makes
// vtkPLYReader reserve gigabytes, read past the end, or abort): the counts are checked against
// what the file can hold first, so that such files end with a sentence, not a crash.
#ifndef catarMeshFileCheck_h
#define catarMeshFileCheck_h

#include <cstdint>
#include <string>

namespace catar
{
/// The largest mesh file read, in bytes (2 GiB).
constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t(1) << 31;

/// The size of a mesh file; false with a sentence in `error` when it cannot be opened or read, or
/// is larger than kMaxMeshFileBytes.
bool MeshFileSize(const std::string& path, std::uint64_t& size, std::string& error);

/// Checks the header of a PLY file (ASCII or binary): its syntax, and that the elements it
/// announces fit in the bytes that follow it (each binary element takes at least the sizes of
/// its properties, each ASCII element at least one line). False with a sentence in `error`.
bool CheckPlyFile(const std::string& path, std::string& error);

/// Checks the counts of a legacy VTK file's sections (POINTS, VERTICES, LINES, POLYGONS,
/// TRIANGLE_STRIPS, POINT_DATA, CELL_DATA): none may announce more values than the file has
/// bytes.
bool CheckLegacyVtkFile(const std::string& path, std::string& error);

/// Checks every face, line and point reference of an OBJ file against the vertices, texture
/// coordinates and normals it has (1-based, or negative: relative).
bool CheckObjFile(const std::string& path, std::string& error);

/// Checks a binary STL file's triangle count against its size (84 + 50 bytes a triangle); ASCII
/// STL files pass.
bool CheckStlFile(const std::string& path, std::string& error);

/// Checks a VTK XML PolyData file (.vtp) as vtkXMLPolyDataReader will read it: every array of
/// every piece holds the values its piece announces (ASCII numbers counted; binary headers read,
/// compressed blocks decompressed to the sizes their table gives), and the cell offsets rise and
/// end inside the connectivity. Implemented in VtpFileCheck.cxx.
bool CheckVtpFile(const std::string& path, std::string& error);

/// About how many triangles a mesh file holds, from its size and format, for a memory estimate
/// before it is read: a binary STL's exact count; for other formats the size over a generous
/// number of bytes a triangle (ASCII STL 250, OBJ 40, PLY and VTK 20), so that the estimate is
/// low rather than high. 0 when the file cannot be read.
double EstimatedMeshTriangles(const std::string& path);

/// The check for a file by its extension (.ply, .vtk, .vtp, .stl, .obj; other files only against
/// kMaxMeshFileBytes). False with a sentence in `error`.
bool CheckMeshFile(const std::string& path, std::string& error);
} // namespace catar

#endif
