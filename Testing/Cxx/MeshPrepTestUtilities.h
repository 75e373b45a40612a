// Helpers shared by the MeshPrep tests: simple meshes built here, the OBJ reader for the shared
// data, and checks of orientation and closedness. VTK-free.
#ifndef catarMeshPrepTestUtilities_h
#define catarMeshPrepTestUtilities_h

#include "TriangleMesh.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

namespace catar_test
{
using catar::Vec3;
using catar::mesh::PointAttribute;
using catar::mesh::TriangleMesh;

/// An axis-aligned box [0, sx] x [0, sy] x [0, sz] of 8 points and 12 triangles, outward.
inline TriangleMesh MakeBox(double sx, double sy, double sz)
{
  TriangleMesh box;
  for (int i = 0; i < 8; ++i)
  {
    box.points.emplace_back((i & 1) ? sx : 0.0, (i & 2) ? sy : 0.0, (i & 4) ? sz : 0.0);
  }
  // Each face as a quad counter-clockwise seen from outside, split along its first diagonal.
  const int quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (const auto& q : quads)
  {
    box.triangles.push_back({ { q[0], q[1], q[2] } });
    box.triangles.push_back({ { q[0], q[2], q[3] } });
  }
  return box;
}

/// A unit-free icosphere of the given radius: the icosahedron subdivided `levels` times with
/// its points pushed onto the sphere, outward.
inline TriangleMesh MakeSphere(double radius, int levels)
{
  TriangleMesh sphere;
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  const double corners[12][3] = { { -1, g, 0 }, { 1, g, 0 }, { -1, -g, 0 }, { 1, -g, 0 },
    { 0, -1, g }, { 0, 1, g }, { 0, -1, -g }, { 0, 1, -g }, { g, 0, -1 }, { g, 0, 1 },
    { -g, 0, -1 }, { -g, 0, 1 } };
  for (const auto& c : corners)
  {
    sphere.points.push_back(radius * Vec3(c[0], c[1], c[2]).normalized());
  }
  sphere.triangles = { { { 0, 11, 5 } }, { { 0, 5, 1 } }, { { 0, 1, 7 } }, { { 0, 7, 10 } },
    { { 0, 10, 11 } }, { { 1, 5, 9 } }, { { 5, 11, 4 } }, { { 11, 10, 2 } }, { { 10, 7, 6 } },
    { { 7, 1, 8 } }, { { 3, 9, 4 } }, { { 3, 4, 2 } }, { { 3, 2, 6 } }, { { 3, 6, 8 } },
    { { 3, 8, 9 } }, { { 4, 9, 5 } }, { { 2, 4, 11 } }, { { 6, 2, 10 } }, { { 8, 6, 7 } },
    { { 9, 8, 1 } } };
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<int, int>, int> midpoints;
    const auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      const auto found = midpoints.find(key);
      if (found != midpoints.end())
      {
        return found->second;
      }
      sphere.points.push_back(radius * (sphere.points[a] + sphere.points[b]).normalized());
      const int m = static_cast<int>(sphere.points.size()) - 1;
      midpoints.emplace(key, m);
      return m;
    };
    std::vector<std::array<int, 3>> triangles;
    for (const auto& t : sphere.triangles)
    {
      const int ab = midpoint(t[0], t[1]);
      const int bc = midpoint(t[1], t[2]);
      const int ca = midpoint(t[2], t[0]);
      triangles.push_back({ { t[0], ab, ca } });
      triangles.push_back({ { ab, t[1], bc } });
      triangles.push_back({ { ca, bc, t[2] } });
      triangles.push_back({ { ab, bc, ca } });
    }
    sphere.triangles = triangles;
  }
  return sphere;
}

/// Adds a point attribute computed from each point's position.
template<typename Function>
void AddPointAttribute(TriangleMesh& mesh, const std::string& name, int components, Function f)
{
  PointAttribute attribute;
  attribute.name = name;
  attribute.components = components;
  for (const Vec3& p : mesh.points)
  {
    for (int k = 0; k < components; ++k)
    {
      attribute.values.push_back(f(p, k));
    }
  }
  mesh.pointData.push_back(attribute);
}

inline const PointAttribute* FindAttribute(const TriangleMesh& mesh, const std::string& name)
{
  for (const PointAttribute& attribute : mesh.pointData)
  {
    if (attribute.name == name)
    {
      return &attribute;
    }
  }
  return nullptr;
}

/// Reads the vertices and faces of an OBJ file (faces with more than three corners are split
/// as fans; "v/vt/vn" corners and negative indices are understood). False when unreadable.
inline bool ReadObj(const std::string& path, TriangleMesh& mesh)
{
  std::ifstream file(path);
  if (!file)
  {
    return false;
  }
  mesh = TriangleMesh();
  std::string line;
  while (std::getline(file, line))
  {
    std::istringstream stream(line);
    std::string tag;
    stream >> tag;
    if (tag == "v")
    {
      Vec3 p;
      stream >> p.x() >> p.y() >> p.z();
      mesh.points.push_back(p);
    }
    else if (tag == "f")
    {
      std::vector<int> corners;
      std::string corner;
      while (stream >> corner)
      {
        const int index = std::atoi(corner.c_str());
        corners.push_back(index < 0 ? static_cast<int>(mesh.points.size()) + index : index - 1);
      }
      for (std::size_t k = 2; k < corners.size(); ++k)
      {
        mesh.triangles.push_back({ { corners[0], corners[k - 1], corners[k] } });
      }
    }
  }
  return !mesh.triangles.empty();
}

/// A file of the shared data folder: $CATAR_SHARED_DATA, else the build's default.
inline std::string SharedDataPath(const std::string& name)
{
  const char* folder = std::getenv("CATAR_SHARED_DATA");
  return std::string(folder && *folder ? folder : CATAR_SHARED_DATA_DEFAULT) + "/" + name;
}

/// The number of times the directed edge a -> b occurs, for every directed edge.
inline std::map<std::pair<int, int>, int> DirectedEdges(const TriangleMesh& mesh)
{
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++edges[{ t[k], t[(k + 1) % 3] }];
    }
  }
  return edges;
}

/// True when no directed edge occurs twice (neighbours run shared edges in opposite directions).
inline bool ConsistentlyOriented(const TriangleMesh& mesh)
{
  for (const auto& entry : DirectedEdges(mesh))
  {
    if (entry.second > 1)
    {
      return false;
    }
  }
  return true;
}

/// Edges with one triangle only.
inline std::size_t CountBoundaryEdges(const TriangleMesh& mesh)
{
  const auto edges = DirectedEdges(mesh);
  std::size_t count = 0;
  for (const auto& entry : edges)
  {
    if (edges.count({ entry.first.second, entry.first.first }) == 0)
    {
      ++count;
    }
  }
  return count;
}

/// Volume enclosed by a closed surface: positive when it is oriented outward.
inline double SignedVolume(const TriangleMesh& mesh)
{
  double volume = 0.0;
  for (const auto& t : mesh.triangles)
  {
    volume += mesh.points[t[0]].dot(mesh.points[t[1]].cross(mesh.points[t[2]])) / 6.0;
  }
  return volume;
}

/// True when one of the warnings contains `text`.
inline bool HasWarning(const catar::mesh::Warnings& warnings, const std::string& text)
{
  for (const std::string& warning : warnings)
  {
    if (warning.find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

} // namespace catar_test

#endif
