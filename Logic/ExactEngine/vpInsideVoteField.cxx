#include "vpInsideVoteField.h"

#include "vpClock.h"
#include "vpInsideVote.h"
#include "vpMemory.h"
#include "vpTriangleGeometry.h"
#include "vpVesselSurface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace vp
{
namespace
{
/// How much wider than the geometry the marks are (mm): the rays are cast in float, relative to
/// the tree's centre, so their origins and the triangles they meet are off by some 1e-5 mm.
constexpr double WidenMm = 1e-3;
/// Beyond this many cells swept per cell of the field, it is not built (see the constructor).
constexpr double MaxSweepsPerCell = 4.0;

std::uint32_t FindRoot(std::vector<std::uint32_t>& parent, std::uint32_t r)
{
  while (parent[r] != r)
  {
    parent[r] = parent[parent[r]];
    r = parent[r];
  }
  return r;
}

/// The edges whose shadows turn a ray's parity: those of an odd number of triangles, and every
/// edge of a triangle without area (the rays never meet it, so its neighbour's edge is a rim).
std::vector<std::array<std::int32_t, 2>> EdgesToSweep(const VesselSurface& surface)
{
  std::vector<std::array<std::int32_t, 2>> edges = surface.OddEdges();
  for (const auto& tri : surface.TriangleArray())
  {
    double ab[3], ac[3], n[3];
    Sub3(surface.Point(tri[1]), surface.Point(tri[0]), ab);
    Sub3(surface.Point(tri[2]), surface.Point(tri[0]), ac);
    Cross3(ab, ac, n);
    const double longest2 = std::max({ Dot3(ab, ab), Dot3(ac, ac), Distance2(surface.Point(tri[1]), surface.Point(tri[2])) });
    if (Dot3(n, n) <= 1e-18 * longest2 * longest2)
    {
      edges.push_back({ tri[0], tri[1] });
      edges.push_back({ tri[1], tri[2] });
      edges.push_back({ tri[2], tri[0] });
    }
  }
  return edges;
}
} // namespace

InsideVoteField::InsideVoteField(
  const VesselSurface& surface, double cellMm, double padMm, std::size_t maxCells, const RayVote& vote)
{
  const double startMs = NowMs();
  const double* b = surface.Bounds();
  // The cell: as asked, or as large as maxCells cells need (in double: a tiny cell would
  // overflow an int's count of them).
  double extent[3];
  for (int a = 0; a < 3; ++a)
  {
    this->OriginMm[a] = b[2 * a] - padMm;
    extent[a] = std::max(b[2 * a + 1] - b[2 * a] + 2.0 * padMm, 1e-6);
  }
  this->EdgeMm = std::max(cellMm, std::cbrt(extent[0] * extent[1] * extent[2] / static_cast<double>(maxCells)));
  for (;;)
  {
    double cells = 1.0, dims[3];
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = std::max(1.0, std::ceil(extent[a] / this->EdgeMm));
      cells *= dims[a];
    }
    if (cells <= static_cast<double>(maxCells))
    {
      for (int a = 0; a < 3; ++a)
      {
        this->Dims[a] = static_cast<int>(dims[a]);
      }
      break;
    }
    this->EdgeMm *= 1.01;
  }
  const std::size_t cells = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  const std::vector<std::array<std::int32_t, 2>> edges = EdgesToSweep(surface);
  this->Swept = edges.size();
  // A surface of many rims (a triangle soup, every edge its own) would have its field marked
  // nearly whole, at a cost of many times its rays: it keeps its rays.
  double diagonal = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    diagonal += extent[a] * extent[a];
  }
  const double steps = std::ceil((std::sqrt(diagonal) + this->EdgeMm) / (0.5 * this->EdgeMm)) + 1.0;
  double sweeps = 0.0;
  for (const auto& edge : edges)
  {
    sweeps += InsideVote::Rays * steps * std::ceil(std::sqrt(Distance2(surface.Point(edge[0]), surface.Point(edge[1]))) / this->EdgeMm);
  }
  if (sweeps > MaxSweepsPerCell * static_cast<double>(cells))
  {
    this->Dims[0] = this->Dims[1] = this->Dims[2] = 0;
    this->BuildTimeMs = NowMs() - startMs;
    return;
  }
  AssignOnHugePages(this->State, cells, static_cast<std::uint8_t>(Clear)); // looked up at random places by batches
  this->MarkTriangles(surface);
  this->MarkShadows(surface, edges);
  this->VoteRegions(vote);
  this->BuildTimeMs = NowMs() - startMs;
}

bool InsideVoteField::CellRange(const double lo[3], const double hi[3], int first[3], int last[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    first[a] = std::max(0, static_cast<int>(std::floor((lo[a] - WidenMm - this->OriginMm[a]) / this->EdgeMm)));
    last[a] = std::min(this->Dims[a] - 1, static_cast<int>(std::floor((hi[a] + WidenMm - this->OriginMm[a]) / this->EdgeMm)));
    if (first[a] > last[a])
    {
      return false;
    }
  }
  return true;
}

void InsideVoteField::MarkBox(const double lo[3], const double hi[3])
{
  int l[3], u[3];
  if (!this->CellRange(lo, hi, l, u))
  {
    return;
  }
  for (int k = l[2]; k <= u[2]; ++k)
  {
    for (int j = l[1]; j <= u[1]; ++j)
    {
      std::uint8_t* row = this->State.data() + (static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0];
      std::fill(row + l[0], row + u[0] + 1, static_cast<std::uint8_t>(Marked));
    }
  }
}

void InsideVoteField::MarkTriangles(const VesselSurface& surface)
{
  const double h = this->EdgeMm;
  for (const auto& tri : surface.TriangleArray())
  {
    const double* p[3] = { surface.Point(tri[0]), surface.Point(tri[1]), surface.Point(tri[2]) };
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min({ p[0][a], p[1][a], p[2][a] });
      hi[a] = std::max({ p[0][a], p[1][a], p[2][a] });
    }
    int l[3], u[3];
    if (!this->CellRange(lo, hi, l, u))
    {
      continue;
    }
    // A cell the triangle's plane misses holds none of it: a large triangle marks only the cells
    // along its plane, not its whole box.
    double ab[3], ac[3], n[3];
    Sub3(p[1], p[0], ab);
    Sub3(p[2], p[0], ac);
    Cross3(ab, ac, n);
    const double reach = 0.5 * h * (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2])) + WidenMm * std::sqrt(Dot3(n, n));
    for (int k = l[2]; k <= u[2]; ++k)
    {
      for (int j = l[1]; j <= u[1]; ++j)
      {
        for (int i = l[0]; i <= u[0]; ++i)
        {
          const double c[3] = { this->OriginMm[0] + (i + 0.5) * h - p[0][0], this->OriginMm[1] + (j + 0.5) * h - p[0][1],
            this->OriginMm[2] + (k + 0.5) * h - p[0][2] };
          if (std::abs(Dot3(n, c)) <= reach)
          {
            this->State[(static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0] + i] = Marked;
          }
        }
      }
    }
  }
}

void InsideVoteField::MarkShadows(const VesselSurface& surface, const std::vector<std::array<std::int32_t, 2>>& edges)
{
  const double h = this->EdgeMm, step = 0.5 * h;
  double boxHi[3];
  for (int a = 0; a < 3; ++a)
  {
    boxHi[a] = this->OriginMm[a] + this->Dims[a] * h;
  }
  for (const auto& edge : edges)
  {
    const double* e0 = surface.Point(edge[0]);
    const double* e1 = surface.Point(edge[1]);
    // In pieces no longer than a cell, so that a piece's box hugs its shadow.
    const int pieces = std::max(1, static_cast<int>(std::ceil(std::sqrt(Distance2(e0, e1)) / h)));
    for (int piece = 0; piece < pieces; ++piece)
    {
      double a[3], c[3];
      for (int x = 0; x < 3; ++x)
      {
        a[x] = e0[x] + (e1[x] - e0[x]) * piece / pieces;
        c[x] = e0[x] + (e1[x] - e0[x]) * (piece + 1) / pieces;
      }
      for (const auto& d : InsideVote::Directions)
      {
        // The points whose ray meets the piece: the piece swept against the ray's direction,
        // marked a half cell at a time until it leaves the box.
        for (double t = 0.0;; t += step)
        {
          double lo[3], hi[3];
          bool outside = false;
          for (int x = 0; x < 3; ++x)
          {
            const double v[4] = { a[x] - t * d[x], c[x] - t * d[x], a[x] - (t + step) * d[x], c[x] - (t + step) * d[x] };
            lo[x] = *std::min_element(v, v + 4);
            hi[x] = *std::max_element(v, v + 4);
            outside = outside || hi[x] + WidenMm < this->OriginMm[x] || lo[x] - WidenMm > boxHi[x];
          }
          if (outside)
          {
            break; // it moves on away from the box
          }
          this->MarkBox(lo, hi);
        }
      }
    }
  }
}

namespace
{
/// A run of cells along x, [X0, X1), in one row (y, z) of the grid.
struct CellRun
{
  int X0, X1;
  std::size_t Row;
};

/// The runs of cells in a given state, row by row; rowStart[row] is the row's first run (rows + 1
/// entries, the last the count).
std::vector<CellRun> RunsOf(const std::vector<std::uint8_t>& state, std::uint8_t wanted, int nx, std::size_t rows,
  std::vector<std::size_t>& rowStart)
{
  std::vector<CellRun> runs;
  rowStart.assign(rows + 1, 0);
  for (std::size_t row = 0; row < rows; ++row)
  {
    rowStart[row] = runs.size();
    const std::uint8_t* s = state.data() + row * nx;
    for (int x = 0; x < nx;)
    {
      if (s[x] != wanted)
      {
        ++x;
        continue;
      }
      const int x0 = x;
      while (x < nx && s[x] == wanted)
      {
        ++x;
      }
      runs.push_back({ x0, x, row });
    }
  }
  rowStart[rows] = runs.size();
  return runs;
}

/// Each run's region: the runs joined to those they touch in the rows below (y - 1) and behind
/// (z - 1), the union's sets; every run's entry is its region's root (a run of its own).
std::vector<std::uint32_t> JoinIntoRegions(const std::vector<CellRun>& runs, const std::vector<std::size_t>& rowStart, std::size_t ny)
{
  std::vector<std::uint32_t> parent(runs.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto join = [&](std::size_t row, std::size_t other) {
    std::size_t i = rowStart[row], j = rowStart[other];
    while (i < rowStart[row + 1] && j < rowStart[other + 1])
    {
      if (runs[i].X0 < runs[j].X1 && runs[j].X0 < runs[i].X1)
      {
        parent[FindRoot(parent, static_cast<std::uint32_t>(i))] = FindRoot(parent, static_cast<std::uint32_t>(j));
      }
      (runs[i].X1 < runs[j].X1 ? i : j)++;
    }
  };
  const std::size_t rows = rowStart.size() - 1;
  for (std::size_t row = 0; row < rows; ++row)
  {
    if (row % ny != 0)
    {
      join(row, row - 1);
    }
    if (row >= ny)
    {
      join(row, row - ny);
    }
  }
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    parent[r] = FindRoot(parent, static_cast<std::uint32_t>(r));
  }
  return parent;
}

/// Per region (indexed by its root): three runs far apart in it, its first, a middle one and its
/// last.
std::vector<std::array<std::uint32_t, 3>> SampledRuns(const std::vector<std::uint32_t>& region)
{
  constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::array<std::uint32_t, 3>> sampled(region.size(), { None, None, None });
  std::vector<std::uint32_t> count(region.size(), 0), seen(region.size(), 0);
  for (std::size_t r = 0; r < region.size(); ++r)
  {
    std::array<std::uint32_t, 3>& s = sampled[region[r]];
    s[0] = s[0] == None ? static_cast<std::uint32_t>(r) : s[0];
    s[2] = static_cast<std::uint32_t>(r);
    ++count[region[r]];
  }
  for (std::size_t r = 0; r < region.size(); ++r)
  {
    const std::uint32_t root = region[r];
    sampled[root][1] = seen[root]++ == count[root] / 2 ? static_cast<std::uint32_t>(r) : sampled[root][1];
  }
  return sampled;
}
} // namespace

void InsideVoteField::VoteRegions(const RayVote& vote)
{
  const int nx = this->Dims[0];
  const std::size_t ny = static_cast<std::size_t>(this->Dims[1]);
  std::vector<std::size_t> rowStart;
  const std::vector<CellRun> runs = RunsOf(this->State, Clear, nx, ny * this->Dims[2], rowStart);
  const std::vector<std::uint32_t> region = JoinIntoRegions(runs, rowStart, ny);
  // Each region's vote: the majority of three points far apart in it (its first cell, a middle
  // run's middle, its last cell; a band behind a fold, see the class comment, is thin, so that
  // two of them rarely fall in bands); no majority leaves it to the rays.
  const std::vector<std::array<std::uint32_t, 3>> sampled = SampledRuns(region);
  const double h = this->EdgeMm;
  std::vector<std::uint8_t> value(runs.size(), Clear);
  for (std::size_t root = 0; root < runs.size(); ++root)
  {
    if (region[root] != root)
    {
      continue;
    }
    // Within their cells, a little off the centre: the samples stay apart when the region is one
    // cell, and off the grid's planes.
    static constexpr double Offsets[3][3] = { { 0.0, 0.0, 0.0 }, { 0.3, 0.2, -0.1 }, { -0.2, -0.3, 0.2 } };
    std::uint8_t votes[3];
    for (int k = 0; k < 3; ++k)
    {
      const CellRun& run = runs[sampled[root][static_cast<std::size_t>(k)]];
      const int x = k == 0 ? run.X0 : k == 1 ? (run.X0 + run.X1) / 2 : run.X1 - 1;
      const double p[3] = { this->OriginMm[0] + (x + 0.5 + Offsets[k][0]) * h,
        this->OriginMm[1] + (static_cast<double>(run.Row % ny) + 0.5 + Offsets[k][1]) * h,
        this->OriginMm[2] + (static_cast<double>(run.Row / ny) + 0.5 + Offsets[k][2]) * h };
      bool uncertain = false;
      const bool inside = vote(p, uncertain);
      votes[k] = static_cast<std::uint8_t>(FirstVote + (inside ? 1 : 0) + (uncertain ? 2 : 0));
    }
    value[root] = votes[0] == votes[1] || votes[0] == votes[2] ? votes[0]
      : votes[1] == votes[2]                      ? votes[1]
                                                  : static_cast<std::uint8_t>(Marked);
    ++this->RegionCount;
  }
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    const std::uint8_t v = value[region[r]];
    std::uint8_t* cells = this->State.data() + runs[r].Row * nx;
    std::fill(cells + runs[r].X0, cells + runs[r].X1, v);
    this->Voted += v == Marked ? 0 : static_cast<std::size_t>(runs[r].X1 - runs[r].X0);
  }
}
} // namespace vp
