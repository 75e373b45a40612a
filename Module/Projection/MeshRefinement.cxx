#include "MeshRefinement.h"

#include "Parallel.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

namespace catar
{
namespace
{
constexpr std::int64_t kGrain = 1024;
// The most rounds of passing edge splits to neighbours.
constexpr int kMaxRounds = 8;

// An edge of the mesh by its end points' positions, the lexicographically smaller first.
using Position = std::array<double, 3>;
using EdgeKey = std::pair<Position, Position>;
struct EdgeKeyHash
{
  std::size_t operator()(const EdgeKey& k) const
  {
    std::size_t h = 0;
    for (const Position* p : { &k.first, &k.second })
    {
      for (const double c : *p)
      {
        h = h * 1000003u ^ std::hash<double>()(c);
      }
    }
    return h;
  }
};

template<typename Index, typename Real>
Position PointAt(const PolygonMeshView<Index, Real>& mesh, std::int64_t i)
{
  const Real* p = mesh.points + 3 * i;
  return Position{ { static_cast<double>(p[0]), static_cast<double>(p[1]),
    static_cast<double>(p[2]) } };
}

// The triangle's corners: world points and projections (status, pixel and mirror point; the
// rest is not read).
template<typename Index, typename Real>
void Corners(const PolygonMeshView<Index, Real>& mesh, const PointProjections& at,
  const std::int64_t* ids, std::array<Vec3, 3>& world, std::array<ProjectedPoint, 3>& projected)
{
  for (int k = 0; k < 3; ++k)
  {
    const Real* p = mesh.points + 3 * ids[k];
    world[k] =
      Vec3(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]));
    projected[k].status = static_cast<ProjectionStatus>(at.status[ids[k]]);
    projected[k].pixel = Vec2(at.pixels[2 * ids[k]], at.pixels[2 * ids[k] + 1]);
    const double* m = at.mirrorPoints + 3 * ids[k];
    projected[k].mirrorPoint = Vec3(m[0], m[1], m[2]);
  }
}

// Edge (a, b) of the mesh and whether a comes first in its key (the parameter along the edge is
// then counted from a).
template<typename Index, typename Real>
EdgeKey Key(const PolygonMeshView<Index, Real>& mesh, std::int64_t a, std::int64_t b, bool& forward)
{
  const Position pa = PointAt(mesh, a), pb = PointAt(mesh, b);
  forward = pa < pb;
  return forward ? EdgeKey(pa, pb) : EdgeKey(pb, pa);
}

// Polygon c's first three point ids (the caller knows it is a triangle).
template<typename Index, typename Real>
std::array<std::int64_t, 3> TriangleAt(const PolygonMeshView<Index, Real>& mesh, std::int64_t c)
{
  const Index* v = mesh.connectivity + mesh.offsets[c];
  return std::array<std::int64_t, 3>{ { static_cast<std::int64_t>(v[0]),
    static_cast<std::int64_t>(v[1]), static_cast<std::int64_t>(v[2]) } };
}

template<typename Index, typename Real>
bool IsTriangle(const PolygonMeshView<Index, Real>& mesh, std::int64_t c)
{
  return mesh.offsets[c + 1] - mesh.offsets[c] == 3;
}

bool Seen(const PointProjections& at, std::int64_t i)
{
  return HasProjection(static_cast<ProjectionStatus>(at.status[i]));
}
} // namespace

template<typename Index, typename Real>
std::vector<std::int64_t> ChooseTriangles(const PolygonMeshView<Index, Real>& mesh,
  const Projector& projector, const TessellationOptions& options, const PointProjections& at,
  int threads)
{
  const std::int64_t nPolys = mesh.numberOfPolygons;
  std::vector<unsigned char> split(static_cast<std::size_t>(nPolys), 0);
  parallel::For(0, nPolys, kGrain, threads, [&](std::int64_t begin, std::int64_t end) {
    std::vector<std::int64_t> cells;
    std::vector<std::array<Vec3, 3>> world;
    std::vector<std::array<ProjectedPoint, 3>> projected;
    for (std::int64_t c = begin; c < end; ++c)
    {
      if (!IsTriangle(mesh, c))
      {
        continue;
      }
      const std::array<std::int64_t, 3> v = TriangleAt(mesh, c);
      const bool allSeen = Seen(at, v[0]) && Seen(at, v[1]) && Seen(at, v[2]);
      const double* const px[3] = { at.pixels + 2 * v[0], at.pixels + 2 * v[1],
        at.pixels + 2 * v[2] };
      if (!NeedsFateCheck(allSeen, px, options))
      {
        continue;
      }
      cells.push_back(c);
      world.emplace_back();
      projected.emplace_back();
      Corners(mesh, at, v.data(), world.back(), projected.back());
    }
    std::vector<TriangleFate> fates(cells.size());
    TriangleFates(projector, cells.size(), world.data(), projected.data(), options, fates.data());
    for (std::size_t k = 0; k < cells.size(); ++k)
    {
      split[cells[k]] = fates[k] == TriangleFate::Tessellate ? 1 : 0;
    }
  });
  std::vector<std::int64_t> chosen;
  for (std::int64_t c = 0; c < nPolys; ++c)
  {
    if (split[c])
    {
      chosen.push_back(c);
    }
  }
  return chosen;
}

template<typename Index, typename Real>
std::vector<Tessellation> TessellateAlike(const PolygonMeshView<Index, Real>& mesh,
  const Projector& projector, const TessellationOptions& options, const PointProjections& at,
  std::vector<std::int64_t>& chosen, std::size_t maxPieces, int threads)
{
  const std::int64_t nPolys = mesh.numberOfPolygons;
  const std::int64_t nPoints = mesh.numberOfPoints;
  // A tessellation per chosen triangle (in parallel); at most maxPieces in all (a tiny tolerance
  // stops there rather than exhausting memory).
  TessellationOptions bounded = options;
  bounded.maxPiecesPerTriangle = static_cast<int>(std::max<std::size_t>(4,
    std::min<std::size_t>(
      static_cast<std::size_t>(options.maxPiecesPerTriangle), maxPieces / chosen.size())));
  // Triangles that share an edge must split it alike (else the halves on one side bend away
  // from the straight edge on the other: a crack). The splits each made on its edges are passed
  // to the triangles across them, which are tessellated again (or for the first time) with those
  // splits forced, until no triangle makes a split its neighbour lacks.
  std::vector<Tessellation> pieces(chosen.size());
  std::vector<TriangleEdgeSplits> forced(chosen.size()), made(chosen.size());
  std::unordered_map<std::int64_t, std::size_t> slot; // cell -> index in chosen
  for (std::size_t k = 0; k < chosen.size(); ++k)
  {
    slot.emplace(chosen[k], k);
  }
  std::unordered_map<EdgeKey, std::vector<double>, EdgeKeyHash> edgeSplits; // canonical t
  // The triangles a round may pass splits to (three points, and a seen corner or chosen now:
  // those that become chosen later have a seen corner), in cell order, with their edges' hashes,
  // found once: each round looks for the changed edges among them by hash first (a bit per hash
  // value, most triangles missing at once), and compares the keys only on a hit.
  std::vector<std::int64_t> eligible;
  std::vector<std::array<std::size_t, 3>> edgeHashes;
  {
    std::vector<unsigned char> isEligible(static_cast<std::size_t>(nPolys), 0);
    parallel::For(0, nPolys, kGrain, threads, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t c = begin; c < end; ++c)
      {
        if (!IsTriangle(mesh, c))
        {
          continue;
        }
        const Index* v = mesh.connectivity + mesh.offsets[c];
        isEligible[c] = Seen(at, v[0]) || Seen(at, v[1]) || Seen(at, v[2]) ? 1 : 0;
      }
    });
    for (const std::int64_t c : chosen)
    {
      isEligible[c] = IsTriangle(mesh, c) ? 1 : isEligible[c];
    }
    for (std::int64_t c = 0; c < nPolys; ++c)
    {
      if (isEligible[c])
      {
        eligible.push_back(c);
      }
    }
    edgeHashes.resize(eligible.size());
    parallel::For(0, static_cast<std::int64_t>(eligible.size()), kGrain, threads,
      [&](std::int64_t begin, std::int64_t end) {
        for (std::int64_t i = begin; i < end; ++i)
        {
          const std::array<std::int64_t, 3> v = TriangleAt(mesh, eligible[i]);
          for (int e = 0; e < 3; ++e)
          {
            bool forward = true;
            edgeHashes[i][e] = EdgeKeyHash()(Key(mesh, v[e], v[(e + 1) % 3], forward));
          }
        }
      });
  }
  constexpr std::size_t kHashBits = std::size_t(1) << 20;
  std::vector<std::uint64_t> changedHashes(kHashBits / 64);
  std::vector<std::size_t> todo(chosen.size());
  std::iota(todo.begin(), todo.end(), std::size_t(0));
  for (int round = 0; !todo.empty() && round < kMaxRounds; ++round)
  {
    parallel::For(0, static_cast<std::int64_t>(todo.size()), 1, threads,
      [&](std::int64_t begin, std::int64_t end) {
        for (std::int64_t i = begin; i < end; ++i)
        {
          const std::size_t k = todo[i];
          const std::array<std::int64_t, 3> v = TriangleAt(mesh, chosen[k]);
          std::array<Vec3, 3> world;
          std::array<ProjectedPoint, 3> projected;
          Corners(mesh, at, v.data(), world, projected);
          pieces[k] = Tessellation();
          made[k] = TriangleEdgeSplits();
          // Ids local to this tessellation, renumbered by the caller.
          TessellateTriangle(projector, chosen[k], v, world, projected, nPoints, bounded, pieces[k],
            &forced[k], &made[k]);
        }
      });
    // The splits not yet known on each edge.
    std::vector<EdgeKey> changed;
    for (const std::size_t k : todo)
    {
      const std::array<std::int64_t, 3> v = TriangleAt(mesh, chosen[k]);
      for (int e = 0; e < 3; ++e)
      {
        bool forward = true;
        const EdgeKey key = Key(mesh, v[e], v[(e + 1) % 3], forward);
        std::vector<double>& known = edgeSplits[key];
        bool grew = false;
        for (const double t : made[k].at[e])
        {
          const double canonical = forward ? t : 1.0 - t;
          if (std::find(known.begin(), known.end(), canonical) == known.end())
          {
            known.push_back(canonical);
            grew = true;
          }
        }
        if (grew)
        {
          changed.push_back(key);
        }
      }
    }
    todo.clear();
    if (changed.empty())
    {
      break;
    }
    // The triangles on those edges (already tessellated, or with a seen corner), with their
    // forced splits.
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    std::fill(changedHashes.begin(), changedHashes.end(), 0);
    for (const EdgeKey& key : changed)
    {
      const std::size_t h = EdgeKeyHash()(key) % kHashBits;
      changedHashes[h / 64] |= std::uint64_t(1) << (h % 64);
    }
    std::vector<std::int64_t> touched;
    for (std::size_t i = 0; i < eligible.size(); ++i)
    {
      bool hit = false;
      for (int e = 0; e < 3; ++e)
      {
        const std::size_t h = edgeHashes[i][e] % kHashBits;
        hit = hit || (changedHashes[h / 64] >> (h % 64)) & 1;
      }
      if (!hit)
      {
        continue;
      }
      const std::array<std::int64_t, 3> v = TriangleAt(mesh, eligible[i]);
      for (int e = 0; e < 3; ++e)
      {
        bool forward = true;
        if (std::binary_search(
              changed.begin(), changed.end(), Key(mesh, v[e], v[(e + 1) % 3], forward)))
        {
          touched.push_back(eligible[i]);
          break;
        }
      }
    }
    for (const std::int64_t c : touched)
    {
      auto found = slot.find(c);
      if (found == slot.end())
      {
        found = slot.emplace(c, chosen.size()).first;
        chosen.push_back(c);
        pieces.emplace_back();
        forced.emplace_back();
        made.emplace_back();
      }
      const std::size_t k = found->second;
      const std::array<std::int64_t, 3> v = TriangleAt(mesh, c);
      for (int e = 0; e < 3; ++e)
      {
        bool forward = true;
        const EdgeKey key = Key(mesh, v[e], v[(e + 1) % 3], forward);
        std::vector<double>& splitsAt = forced[k].at[e];
        splitsAt.clear();
        const auto known = edgeSplits.find(key);
        if (known != edgeSplits.end())
        {
          for (const double canonical : known->second)
          {
            splitsAt.push_back(forward ? canonical : 1.0 - canonical);
          }
        }
        std::sort(splitsAt.begin(), splitsAt.end());
      }
      todo.push_back(k);
    }
  }
  // Output order: the input's.
  std::vector<std::size_t> order(chosen.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(),
    [&](std::size_t x, std::size_t y) { return chosen[x] < chosen[y]; });
  std::vector<std::int64_t> sortedCells(chosen.size());
  std::vector<Tessellation> sortedPieces(chosen.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    sortedCells[i] = chosen[order[i]];
    sortedPieces[i] = std::move(pieces[order[i]]);
  }
  chosen.swap(sortedCells);
  return sortedPieces;
}

#define CATAR_REFINEMENT_INSTANTIATE(Index, Real)                                                  \
  template std::vector<std::int64_t> ChooseTriangles<Index, Real>(                                 \
    const PolygonMeshView<Index, Real>&, const Projector&, const TessellationOptions&,             \
    const PointProjections&, int);                                                                 \
  template std::vector<Tessellation> TessellateAlike<Index, Real>(                                 \
    const PolygonMeshView<Index, Real>&, const Projector&, const TessellationOptions&,             \
    const PointProjections&, std::vector<std::int64_t>&, std::size_t, int);
CATAR_REFINEMENT_INSTANTIATE(int, float)
CATAR_REFINEMENT_INSTANTIATE(long, float)
CATAR_REFINEMENT_INSTANTIATE(long long, float)
CATAR_REFINEMENT_INSTANTIATE(int, double)
CATAR_REFINEMENT_INSTANTIATE(long, double)
CATAR_REFINEMENT_INSTANTIATE(long long, double)
#undef CATAR_REFINEMENT_INSTANTIATE
} // namespace catar
