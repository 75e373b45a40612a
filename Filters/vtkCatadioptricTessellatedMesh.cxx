#include "vtkCatadioptricTessellatedMesh.h"

#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

namespace
{
constexpr vtkIdType kGrain = 1024;
// The most pieces one execution makes (all split triangles together).
constexpr std::size_t kMaxPieces = std::size_t(1) << 22;
// The most rounds of passing edge splits to neighbours.
constexpr int kMaxRounds = 8;

// An edge of the input mesh by its end points' positions, the lexicographically smaller first:
// faces that do not share point ids (a box with a normal per face) still share their edges.
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

// The triangle's corners: world points and projections (status, pixel and mirror point; the
// rest is not read).
void Corners(vtkPoints* points, const unsigned char* status, const double* pixels,
  const double* mirrorPoints, const vtkIdType* ids, std::array<catar::Vec3, 3>& world,
  std::array<catar::ProjectedPoint, 3>& projected)
{
  for (int k = 0; k < 3; ++k)
  {
    double p[3];
    points->GetPoint(ids[k], p);
    world[k] = catar::Vec3(p[0], p[1], p[2]);
    projected[k].status = static_cast<catar::ProjectionStatus>(status[ids[k]]);
    projected[k].pixel = catar::Vec2(pixels[2 * ids[k]], pixels[2 * ids[k] + 1]);
    const double* m = mirrorPoints + 3 * ids[k];
    projected[k].mirrorPoint = catar::Vec3(m[0], m[1], m[2]);
  }
}
// Edge (a, b) of the input and whether a comes first in its key (the parameter along the edge is
// then counted from a).
EdgeKey Key(vtkPoints* points, vtkIdType a, vtkIdType b, bool& forward)
{
  Position pa, pb;
  points->GetPoint(a, pa.data());
  points->GetPoint(b, pb.data());
  forward = pa < pb;
  return forward ? EdgeKey(pa, pb) : EdgeKey(pb, pa);
}

// The triangles to split this frame, in cell order: a quick pass on the corners' statuses and
// edge lengths (catar::NeedsFateCheck), then the fate of each triangle that needs it.
std::vector<vtkIdType> ChooseTriangles(vtkPolyData* input, const catar::Projector& projector,
  const catar::TessellationOptions& options, const unsigned char* status, const double* pixels,
  const double* mirrorPoints)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  vtkPoints* points = input->GetPoints();
  std::vector<unsigned char> split(static_cast<std::size_t>(nPolys), 0);
  polys->Visit([&](auto& state) {
    const auto* offsets = state.GetOffsets()->GetPointer(0);
    const auto* connectivity = state.GetConnectivity()->GetPointer(0);
    vtkCatadioptricParallel::For(0, nPolys, kGrain, [&](vtkIdType begin, vtkIdType end) {
      std::vector<vtkIdType> cells;
      std::vector<std::array<catar::Vec3, 3>> world;
      std::vector<std::array<catar::ProjectedPoint, 3>> projected;
      for (vtkIdType c = begin; c < end; ++c)
      {
        if (offsets[c + 1] - offsets[c] != 3)
        {
          continue;
        }
        const vtkIdType v[3] = { static_cast<vtkIdType>(connectivity[offsets[c]]),
          static_cast<vtkIdType>(connectivity[offsets[c] + 1]),
          static_cast<vtkIdType>(connectivity[offsets[c] + 2]) };
        const bool allSeen =
          catar::HasProjection(static_cast<catar::ProjectionStatus>(status[v[0]])) &&
          catar::HasProjection(static_cast<catar::ProjectionStatus>(status[v[1]])) &&
          catar::HasProjection(static_cast<catar::ProjectionStatus>(status[v[2]]));
        const double* const px[3] = { pixels + 2 * v[0], pixels + 2 * v[1], pixels + 2 * v[2] };
        if (!catar::NeedsFateCheck(allSeen, px, options))
        {
          continue;
        }
        cells.push_back(c);
        world.emplace_back();
        projected.emplace_back();
        Corners(points, status, pixels, mirrorPoints, v, world.back(), projected.back());
      }
      std::vector<catar::TriangleFate> fates(cells.size());
      catar::TriangleFates(
        projector, cells.size(), world.data(), projected.data(), options, fates.data());
      for (std::size_t k = 0; k < cells.size(); ++k)
      {
        split[cells[k]] = fates[k] == catar::TriangleFate::Tessellate ? 1 : 0;
      }
    });
  });
  std::vector<vtkIdType> chosen;
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    if (split[c])
    {
      chosen.push_back(c);
    }
  }
  return chosen;
}

// The pieces of the chosen triangles (and of the neighbours that must split a shared edge too,
// added to `chosen`), in cell order.
std::vector<catar::Tessellation> TessellateAlike(vtkPolyData* input,
  const catar::Projector& projector, const catar::TessellationOptions& options,
  const unsigned char* status, const double* pixels, const double* mirrorPoints,
  std::vector<vtkIdType>& chosen)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  vtkPoints* points = input->GetPoints();
  const vtkIdType nPoints = input->GetNumberOfPoints();
  // A tessellation per chosen triangle (in parallel); at most kMaxPieces in all (a tiny tolerance
  // stops there rather than exhausting memory).
  catar::TessellationOptions bounded = options;
  bounded.maxPiecesPerTriangle = static_cast<int>(std::max<std::size_t>(4,
    std::min<std::size_t>(
      static_cast<std::size_t>(options.maxPiecesPerTriangle), kMaxPieces / chosen.size())));
  // Triangles that share an edge must split it alike (else the halves on one side bend away
  // from the straight edge on the other: a crack). The splits each made on its edges are passed
  // to the triangles across them, which are tessellated again (or for the first time) with those
  // splits forced, until no triangle makes a split its neighbour lacks.
  std::vector<catar::Tessellation> pieces(chosen.size());
  std::vector<catar::TriangleEdgeSplits> forced(chosen.size()), made(chosen.size());
  std::unordered_map<vtkIdType, std::size_t> slot; // cell -> index in chosen
  for (std::size_t k = 0; k < chosen.size(); ++k)
  {
    slot.emplace(chosen[k], k);
  }
  std::unordered_map<EdgeKey, std::vector<double>, EdgeKeyHash> edgeSplits; // canonical t
  // The triangles a round may pass splits to (three points, and a seen corner or chosen now:
  // those that become chosen later have a seen corner), in cell order, with their edges' hashes,
  // found once: each round looks for the changed edges among them by hash first (a bit per hash
  // value, most triangles missing at once), and compares the keys only on a hit.
  std::vector<vtkIdType> eligible;
  std::vector<std::array<std::size_t, 3>> edgeHashes;
  {
    std::vector<unsigned char> isEligible(static_cast<std::size_t>(nPolys), 0);
    polys->Visit([&](auto& state) {
      const auto* offsets = state.GetOffsets()->GetPointer(0);
      const auto* connectivity = state.GetConnectivity()->GetPointer(0);
      vtkCatadioptricParallel::For(0, nPolys, kGrain, [&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType c = begin; c < end; ++c)
        {
          if (offsets[c + 1] - offsets[c] != 3)
          {
            continue;
          }
          const auto* v = connectivity + offsets[c];
          isEligible[c] =
            catar::HasProjection(static_cast<catar::ProjectionStatus>(status[v[0]])) ||
              catar::HasProjection(static_cast<catar::ProjectionStatus>(status[v[1]])) ||
              catar::HasProjection(static_cast<catar::ProjectionStatus>(status[v[2]]))
            ? 1
            : 0;
        }
      });
    });
    for (const vtkIdType c : chosen)
    {
      isEligible[c] = polys->GetCellSize(c) == 3 ? 1 : isEligible[c];
    }
    for (vtkIdType c = 0; c < nPolys; ++c)
    {
      if (isEligible[c])
      {
        eligible.push_back(c);
      }
    }
    edgeHashes.resize(eligible.size());
    vtkCatadioptricParallel::For(
      0, static_cast<vtkIdType>(eligible.size()), kGrain, [&](vtkIdType begin, vtkIdType end) {
        vtkNew<vtkIdList> ids;
        for (vtkIdType i = begin; i < end; ++i)
        {
          vtkIdType n = 0;
          const vtkIdType* v = nullptr;
          polys->GetCellAtId(eligible[i], n, v, ids);
          for (int e = 0; e < 3; ++e)
          {
            bool forward = true;
            edgeHashes[i][e] = EdgeKeyHash()(Key(points, v[e], v[(e + 1) % 3], forward));
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
    vtkCatadioptricParallel::For(
      0, static_cast<vtkIdType>(todo.size()), 1, [&](vtkIdType begin, vtkIdType end) {
        vtkNew<vtkIdList> ids;
        for (vtkIdType i = begin; i < end; ++i)
        {
          const std::size_t k = todo[i];
          polys->GetCellAtId(chosen[k], ids);
          const vtkIdType* v = ids->GetPointer(0);
          std::array<catar::Vec3, 3> world;
          std::array<catar::ProjectedPoint, 3> projected;
          Corners(points, status, pixels, mirrorPoints, v, world, projected);
          pieces[k] = catar::Tessellation();
          made[k] = catar::TriangleEdgeSplits();
          // Ids local to this tessellation, renumbered below.
          catar::TessellateTriangle(projector, chosen[k], { { v[0], v[1], v[2] } }, world,
            projected, nPoints, bounded, pieces[k], &forced[k], &made[k]);
        }
      });
    // The splits not yet known on each edge.
    std::vector<EdgeKey> changed;
    vtkNew<vtkIdList> ids;
    for (const std::size_t k : todo)
    {
      polys->GetCellAtId(chosen[k], ids);
      for (int e = 0; e < 3; ++e)
      {
        bool forward = true;
        const EdgeKey key = Key(points, ids->GetId(e), ids->GetId((e + 1) % 3), forward);
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
    std::vector<vtkIdType> touched;
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
      vtkIdType n = 0;
      const vtkIdType* v = nullptr;
      polys->GetCellAtId(eligible[i], n, v, ids);
      for (int e = 0; e < 3; ++e)
      {
        bool forward = true;
        if (std::binary_search(
              changed.begin(), changed.end(), Key(points, v[e], v[(e + 1) % 3], forward)))
        {
          touched.push_back(eligible[i]);
          break;
        }
      }
    }
    for (const vtkIdType c : touched)
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
      polys->GetCellAtId(c, ids);
      for (int e = 0; e < 3; ++e)
      {
        bool forward = true;
        const EdgeKey key = Key(points, ids->GetId(e), ids->GetId((e + 1) % 3), forward);
        std::vector<double>& at = forced[k].at[e];
        at.clear();
        const auto known = edgeSplits.find(key);
        if (known != edgeSplits.end())
        {
          for (const double canonical : known->second)
          {
            at.push_back(forward ? canonical : 1.0 - canonical);
          }
        }
        std::sort(at.begin(), at.end());
      }
      todo.push_back(k);
    }
  }
  // Output order: the input's.
  {
    std::vector<std::size_t> order(chosen.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(),
      [&](std::size_t x, std::size_t y) { return chosen[x] < chosen[y]; });
    std::vector<vtkIdType> sortedCells(chosen.size());
    std::vector<catar::Tessellation> sortedPieces(chosen.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      sortedCells[i] = chosen[order[i]];
      sortedPieces[i] = std::move(pieces[order[i]]);
    }
    chosen.swap(sortedCells);
    pieces.swap(sortedPieces);
  }
  return pieces;
}

// The refined mesh: the input's points then the new ones (point data interpolated), the
// polygons with each chosen triangle's pieces in its place (its cell data copied); `sources` (may
// be null): each output cell's input cell, -1 for a piece.
void Assemble(vtkPolyData* input, const std::vector<vtkIdType>& chosen,
  std::vector<catar::Tessellation>& pieces, catar::Tessellation& added, vtkPolyData* output,
  std::vector<vtkIdType>* sources)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  vtkPoints* points = input->GetPoints();
  const vtkIdType nPoints = input->GetNumberOfPoints();
  added.points.clear();
  added.triangles.clear();
  std::vector<std::vector<catar::TessellatedTriangle>> byCell(chosen.size());
  for (std::size_t k = 0; k < chosen.size(); ++k)
  {
    const std::int64_t shift = static_cast<std::int64_t>(added.points.size());
    for (catar::TessellatedTriangle t : pieces[k].triangles)
    {
      for (std::int64_t& id : t.points)
      {
        id = id < nPoints ? id : id + shift;
      }
      byCell[k].push_back(t);
    }
    added.points.insert(added.points.end(), pieces[k].points.begin(), pieces[k].points.end());
  }

  // Points and point data: the input's, then the new ones interpolated.
  const vtkIdType nNew = static_cast<vtkIdType>(added.points.size());
  vtkNew<vtkPoints> outPoints;
  outPoints->SetDataTypeToDouble();
  outPoints->SetNumberOfPoints(nPoints + nNew);
  outPoints->GetData()->InsertTuples(0, nPoints, 0, points->GetData());
  vtkPointData* inPD = input->GetPointData();
  vtkNew<vtkPointData> outPD;
  outPD->InterpolateAllocate(inPD, nPoints + nNew);
  outPD->CopyData(inPD, 0, nPoints, 0);
  vtkNew<vtkIdList> parents;
  parents->SetNumberOfIds(3);
  for (vtkIdType i = 0; i < nNew; ++i)
  {
    const catar::TessellatedPoint& p = added.points[i];
    outPoints->SetPoint(nPoints + i, p.world.data());
    double weights[3];
    for (int k = 0; k < 3; ++k)
    {
      parents->SetId(k, p.parents[k]);
      weights[k] = p.weights[k];
    }
    outPD->InterpolatePoint(inPD, nPoints + i, parents, weights);
  }

  // Cells: verts and lines as they are, the polygons with the split ones' pieces in place, the
  // strips; cell data copied from each piece's triangle.
  vtkCellData* inCD = input->GetCellData();
  vtkNew<vtkCellData> outCD;
  vtkIdType nPieces = 0;
  for (const auto& cell : byCell)
  {
    nPieces += static_cast<vtkIdType>(cell.size());
  }
  const vtkIdType nVerts = input->GetNumberOfVerts(), nLines = input->GetNumberOfLines();
  const vtkIdType nCellsOut =
    input->GetNumberOfCells() - static_cast<vtkIdType>(chosen.size()) + nPieces;
  outCD->CopyAllocate(inCD, nCellsOut);
  // Each output cell's input cell, copied in one call at the end.
  vtkNew<vtkIdList> from;
  from->Allocate(nCellsOut);
  if (sources)
  {
    sources->clear();
    sources->reserve(static_cast<std::size_t>(nCellsOut));
  }
  const auto add = [&](vtkIdType inCell, bool piece) {
    from->InsertNextId(inCell);
    if (sources)
    {
      sources->push_back(piece ? -1 : inCell);
    }
  };
  for (vtkIdType c = 0; c < nVerts + nLines; ++c)
  {
    add(c, false);
  }
  vtkNew<vtkCellArray> outPolys;
  outPolys->AllocateEstimate(nPolys - static_cast<vtkIdType>(chosen.size()) + nPieces, 3);
  vtkNew<vtkIdList> ids;
  std::size_t next = 0;
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    const vtkIdType inCell = nVerts + nLines + c;
    if (next < chosen.size() && chosen[next] == c)
    {
      for (const catar::TessellatedTriangle& t : byCell[next])
      {
        const vtkIdType tri[3] = { t.points[0], t.points[1], t.points[2] };
        outPolys->InsertNextCell(3, tri);
        add(inCell, true);
      }
      ++next;
      continue;
    }
    polys->GetCellAtId(c, ids);
    outPolys->InsertNextCell(ids);
    add(inCell, false);
  }
  const vtkIdType firstStrip = nVerts + nLines + nPolys;
  for (vtkIdType c = 0; c < input->GetNumberOfStrips(); ++c)
  {
    add(firstStrip + c, false);
  }
  outCD->CopyData(inCD, from.Get(), vtkIdType(0));
  output->Initialize();
  output->SetPoints(outPoints);
  output->SetVerts(input->GetVerts());
  output->SetLines(input->GetLines());
  output->SetPolys(outPolys);
  output->SetStrips(input->GetStrips());
  output->GetPointData()->ShallowCopy(outPD);
  output->GetCellData()->ShallowCopy(outCD);
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
}
} // namespace

vtkIdType vtkCatadioptricTessellatedMesh::Refine(vtkPolyData* input,
  const catar::Projector& projector, const catar::TessellationOptions& options,
  const unsigned char* status, const double* pixels, const double* mirrorPoints,
  catar::Tessellation& added, vtkPolyData* output, std::vector<vtkIdType>* sources)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  if (nPolys == 0 || !(options.boundaryTolerance > 0.0 || options.bendTolerance > 0.0))
  {
    return 0;
  }
  const vtkIdType nPoints = input->GetNumberOfPoints();
  // With neither tolerance only triangles with an unseen corner can need it: none when every
  // point is seen, found without a pass over the cells. (With a boundary tolerance, a triangle
  // seen at its corners may still have a hidden middle: the pass looks at those with long edges.)
  if (!(options.bendTolerance > 0.0) && !(options.boundaryTolerance > 0.0) &&
    std::all_of(status, status + nPoints, [](unsigned char s) {
      return catar::HasProjection(static_cast<catar::ProjectionStatus>(s));
    }))
  {
    return 0;
  }
  std::vector<vtkIdType> chosen =
    ChooseTriangles(input, projector, options, status, pixels, mirrorPoints);
  if (chosen.empty())
  {
    return 0;
  }
  std::vector<catar::Tessellation> pieces =
    TessellateAlike(input, projector, options, status, pixels, mirrorPoints, chosen);
  Assemble(input, chosen, pieces, added, output, sources);
  return static_cast<vtkIdType>(chosen.size());
}
