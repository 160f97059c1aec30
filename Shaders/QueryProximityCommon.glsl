// Shared by the two query passes, QueryProximity.comp (one invocation per tile of 8 x 8 pixels,
// for CPU devices) and QueryProximityPerPixel.comp (one invocation per pixel, for GPUs): the
// bindings, the parameters, and every step of a query but the loop over a tile's pixels.
// Both passes give the same answers, bit for bit (see QueryProximityPerPixel.comp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "DepthLayersCommon.glsl"

layout(std430, binding = 0) readonly buffer Occupancy { uint Occupied[]; };
layout(std430, binding = 1) readonly buffer Crossings { uint Crossing[]; };
layout(std430, binding = 2) readonly buffer DepthRanges { uint DepthRange[]; };
// Per class and tile (8 x 8 pixels), then per class and coarse tile (32 x 32): its lowest and
// highest occupied slice, each shifted above the bits that name a pixel of the tile whose column
// has it (SummarizeTiles.comp); lowest > highest when the tile is empty.
layout(std430, binding = 3) readonly buffer TileRanges { uint TileRange[]; };
const uint TilePixelBits = 6u;
const uint CoarsePixelBits = 10u;
layout(std430, binding = 4) readonly buffer TileOrder { ivec2 Order[]; };
// Per point and class, 32 words: [0] best distance (float bits, starts at the range), [1] inside,
// [2] directional distance (float bits), [3..6] the chosen record (ReduceProximity.comp),
// [8..31] the paper's distance bits.
layout(std430, binding = 5) buffer QueryState { uint State[]; };
// Per point, class and tile: distance (float bits), pixel, depth of the closest point (float bits).
layout(std430, binding = 6) writeonly buffer Records { uvec4 Record[]; };
// Per point: the tip in grid units (pixels, pixels, slices), then the unit axis in mm (or zero).
layout(std430, binding = 7) readonly buffer Points { vec4 Point[]; };
// Per point and class, the record chosen so far: the distance's float bits above, the record's
// index (its entry in the order table) below, so that the 64-bit minimum is the least distance
// and, among equal ones, the lowest-numbered record, the one the host once found by scanning
// them all. All ones before any record is offered (ReduceProximity.comp resets it).
layout(std430, binding = 8) buffer Choices { uint64_t Choice[]; };
// Per point and class, a distance the answer is known not to exceed (float bits, mm; +infinity
// when none is known): the host's bound from the vessels' coarse blocks or from the answer before;
// and the entries of the order table within it (the tiles after them are farther from every tip
// of the centre tile). Tiles farther than it are skipped from the start, as they would be once
// the best was found; on a GPU, where a dispatch's tiles all start at once, they would otherwise
// all do their work. The entries after an answer's end leave at once: the dispatch reaches as far
// as the batch's highest ceiling, most answers' ends come long before it.
layout(std430, binding = 9) readonly buffer Ceilings { uvec2 AnswerCeiling[]; };
// The tiles a submission has to visit (stage SelectTiles writes them, VisitListedTiles reads
// them): per listed tile its answer (point x classes + class) and its entry
// in the order table. Packed, so that the visiting threads all have a tile's work to do: on a GPU
// a dispatch over the whole order table starts a workgroup for every tile, nearly all of which
// then find nothing to do; on a CPU device the SIMD lanes of a tile that has no work wait for
// those that have.
layout(std430, binding = 10) buffer TileList { uvec2 ListedTile[]; };
// [0] tiles listed; [1..3] the visiting dispatch's VkDispatchIndirectCommand: a workgroup for
// every TilesPerGroup tiles listed, in rows of ListRowGroups (a device need take no more than
// 65,535 workgroups along x; short rows waste little in the last one, and a batch of the
// phantom's tips fills several, which the tests so cover). ReduceProximity.comp resets it to no
// workgroups for the next query.
layout(std430, binding = 11) buffer TileListSize { uint ListSize[]; };
const uint ListRowGroups = 1024u;
// The listing walks coarse tiles of CoarseTiles x CoarseTiles tiles, nearest first, and looks
// into those that can hold the answer: at 0.1 mm cells a tile is 0.8 mm across, and a tip 20 mm
// from a class had some two thousand tiles of empty space between it and the vessel to test one
// by one (the coarse tiles' ranges follow the fine ones in TileRanges). CoarseOffset: the order
// table of the coarse tiles, offsets from the one holding the centre tile; EntryOf: per offset
// from the centre tile within OrderReach, its entry in the order table (the records and their
// ties are numbered by entry, whichever way a tile is found).
layout(std430, binding = 12) readonly buffer CoarseOrder { ivec2 CoarseOffset[]; };
layout(std430, binding = 13) readonly buffer EntryIndex { uint EntryOf[]; };
const int CoarseTiles = 4;
// A few tips' tiles listed by the host (stage VisitHostListedTiles; vp::HostTileListing), in
// memory the host writes: HostListItemsPerPoint items per point of the slot, from the slot's
// first point on; the first item holds the count, then per item its answer and its entry, or
// LaneItem plus a lane (a workgroup of 64 lanes per pixel) of the answer's "inside" and
// directional walk. The device's own listing is a dispatch more, which a single tip pays in full.
layout(std430, binding = 14) readonly buffer HostTileList { uvec2 HostItem[]; };
const uint HostListItemsPerPoint = 8u;
const uint LaneItem = 0x80000000u;

layout(push_constant) uniform Parameters
{
  float PixelMm;
  float SliceMm;
  float RangeMm;
  float HalfDiagonalMm;
  float BinWidthMm;
  int Bins;
  int Nx;
  int Ny;
  int Nz;
  int Words;
  int TilesX;
  int TilesY;
  int OrderCount;
  int PaperMode;
  uint RangeStride;
  int Classes;
  int DirectionalLanes;
  // This dispatch's part of the order table (and, past its end, of the lanes): a batch first
  // visits the tiles nearest each tip, then the rest, which the best found so far mostly skips.
  int FirstEntry;
  int EndEntry;
  // The directional lanes this dispatch runs before its tiles (invocations per tile, workgroups
  // per pixel; 0 in a batch's first dispatch): the tiles after them are as many as the host
  // writes for this submission.
  int LaneSlots;
  // What this dispatch does (VisitOrderedTiles, SelectTiles, VisitListedTiles), and how many
  // listed tiles one workgroup of the visiting dispatch takes (64 per tile, 1 per pixel).
  int Stage;
  int TilesPerGroup;
  // The order table's reach (tiles from the centre tile) and the coarse order table's length.
  int OrderReach;
  int CoarseCount;
  // Where this submission's points and ceilings start in theirs (a point's place in its slot:
  // the host writes the next submission's while the device reads this one's).
  int FirstPoint;
  // The submission's answers (points x classes): stage SelectTilesPerAnswer's invocations.
  int AnswerCount;
} P;

const int VisitOrderedTiles = 0;    // the order table's entries FirstEntry..EndEntry, after the lanes
const int SelectTiles = 1;          // the same entries, listed when they have to be visited
const int VisitListedTiles = 2;     // the tiles listed
const int SelectTilesPerAnswer = 3; // as SelectTiles, an invocation walking each answer's entries
const int VisitHostListedTiles = 4; // the tiles (and lanes) the host listed

// This invocation's point (set first thing in main), the least of the range and its answer's
// ceiling, and the end of its entries (BeginAnswer).
vec3 Tip;
vec3 AxisMm;
float Ceiling;
uint EntryEnd;
// Stage SelectTilesPerAnswer's best so far: its invocation alone lists its answer, so the best
// stays in a register, not in an atomic on the state (SelectAnswerTiles stores it at the end).
float OwnBest = uintBitsToFloat(0x7F800000u);

// glslang 12 rejects a global const initialised from uintBitsToFloat.
#define Inf uintBitsToFloat(0x7F800000u)
const uint StateStride = 32u;


bool Occupied3(uint cls, ivec3 cell)
{
  uint pixels = uint(P.Nx * P.Ny);
  uint base = ColumnBase(cls, uint(cell.y * P.Nx + cell.x), uint(P.Words), pixels);
  return (Occupied[base + uint(cell.z >> 5)] & (1u << uint(cell.z & 31))) != 0u;
}

// The ray's parameter (mm along the axis) where it crosses the plane at grid coordinate boundary
// of axis k; Inf along an axis the ray does not move on.
float CrossingMm(int k, float boundary, vec3 dirGrid)
{
  return dirGrid[k] == 0.0 ? Inf : (boundary - Tip[k]) / dirGrid[k];
}

// Where the ray enters cell: the last of its three slab entries (0 for the tip's own cell).
// Computed from the cell alone, so every lane that walks through a cell gives it the same value.
float EntryMm(ivec3 cell, vec3 dirGrid)
{
  float t = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    if (dirGrid[k] != 0.0)
    {
      t = max(t, CrossingMm(k, float(cell[k]) + (dirGrid[k] > 0.0 ? 0.0 : 1.0), dirGrid));
    }
  }
  return t;
}

// Directional distance: walk the cells along the axis (Amanatides & Woo) to the first occupied
// one. Its entry distance is never more than the true distance to the surface along the axis.
// Lane `lane` of DirectionalLanes walks its share of the range, the cells entered between
// RangeMm * lane / lanes and RangeMm * (lane + 1) / lanes, starting from the cell holding the
// ray's point at the start of its share; every crossing is computed from the cell, not summed
// step by step, so a lane walks the cells a single walk would and gives each the same entry
// distance. The least entry over the lanes is the single walk's answer, and on a GPU no thread
// walks more than its share (one lane on a CPU device).
float Directional(uint cls, int lane)
{
  vec3 dirGrid = vec3(AxisMm.xy / P.PixelMm, AxisMm.z / P.SliceMm); // cells per mm
  float lanes = float(P.DirectionalLanes);
  float startMm = P.RangeMm * float(lane) / lanes;
  float endMm = lane + 1 == P.DirectionalLanes ? P.RangeMm : P.RangeMm * float(lane + 1) / lanes;
  ivec3 cell = ivec3(floor(Tip + dirGrid * startMm));
  ivec3 stepDir = ivec3(sign(dirGrid));
  int maxSteps = (int(P.RangeMm / P.PixelMm) * 2 + int(P.RangeMm / P.SliceMm)) / P.DirectionalLanes + 8;
  for (int s = 0; s < maxSteps; ++s)
  {
    float tEnter = EntryMm(cell, dirGrid);
    if (tEnter > endMm)
    {
      break;
    }
    if (all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(cell, ivec3(P.Nx, P.Ny, P.Nz))) && Occupied3(cls, cell))
    {
      return tEnter;
    }
    vec3 tMax;
    for (int k = 0; k < 3; ++k)
    {
      tMax[k] = CrossingMm(k, float(cell[k]) + (dirGrid[k] > 0.0 ? 1.0 : 0.0), dirGrid);
    }
    int k = (tMax.x < tMax.y) ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
    cell[k] += stepDir[k];
  }
  return Inf;
}

// Whether the tip is inside: the parity of the centre-ray crossings below the tip's slice. A
// crossing in the tip's own slice leaves the side undecided; the answer is then "inside", which
// overstates danger within one cell of the surface rather than hiding a breach.
uint Inside(uint cls)
{
  ivec3 cell = ivec3(floor(Tip));
  if (cell.x < 0 || cell.y < 0 || cell.x >= P.Nx || cell.y >= P.Ny || cell.z < 0)
  {
    return 0u;
  }
  uint pixels = uint(P.Nx * P.Ny);
  uint base = ColumnBase(cls, uint(cell.y * P.Nx + cell.x), uint(P.Words), pixels);
  int below = min(cell.z, P.Nz);
  uint parity = 0u;
  for (int w = 0; w * 32 < below; ++w)
  {
    uint bits = Crossing[base + uint(w)];
    int n = below - w * 32;
    if (n < 32)
    {
      bits &= (1u << uint(n)) - 1u;
    }
    parity ^= uint(bitCount(bits)) & 1u;
  }
  if (cell.z < P.Nz && (Crossing[base + uint(cell.z >> 5)] & (1u << uint(cell.z & 31))) != 0u)
  {
    return 1u;
  }
  return parity;
}

// Distance in slices from the tip's depth to the nearest occupied slice of the column at base,
// looking no further than window slices; Inf when there is none. depth receives the point of that
// slice nearest the tip.
float NearestSlice(uint base, float window, out float depth)
{
  float tz = Tip.z;
  int start = clamp(int(floor(tz)), 0, P.Nz - 1);
  float best = Inf;
  depth = 0.0;
  // Upwards, from the tip's slice.
  for (int w = start >> 5; w < P.Words; ++w)
  {
    if (float(w * 32) - tz > window)
    {
      break;
    }
    uint bits = Occupied[base + uint(w)];
    if (w == (start >> 5))
    {
      bits &= ~((1u << uint(start & 31)) - 1u);
    }
    if (bits != 0u)
    {
      int s = w * 32 + findLSB(bits);
      float d = max(0.0, float(s) - tz);
      if (d < best)
      {
        best = d;
        depth = clamp(tz, float(s), float(s + 1));
      }
      break;
    }
  }
  // Downwards, from the tip's slice.
  for (int w = start >> 5; w >= 0; --w)
  {
    if (tz - float(w * 32 + 32) > window)
    {
      break;
    }
    uint bits = Occupied[base + uint(w)];
    if (w == (start >> 5))
    {
      uint keep = uint(start & 31);
      bits &= (keep == 31u) ? 0xFFFFFFFFu : ((1u << (keep + 1u)) - 1u);
    }
    if (bits != 0u)
    {
      int s = w * 32 + findMSB(bits);
      float d = max(0.0, tz - float(s + 1));
      if (d < best)
      {
        best = d;
        depth = clamp(tz, float(s), float(s + 1));
      }
      break;
    }
  }
  return best;
}

float AxisGap(float x, float lo, float hi)
{
  return max(0.0, max(lo - x, x - hi));
}

// This invocation's point, in grid units, and its axis.
void BeginPoint(uint point)
{
  uint at = 2u * (uint(P.FirstPoint) + point);
  Tip = Point[at].xyz;
  AxisMm = Point[at + 1u].xyz;
}

// The invocations after the last tile: lane 0 answers "inside", every lane its share of the
// directional walk.
void AnswerLane(uint cls, uint stateBase, int lane)
{
  if (lane >= P.DirectionalLanes)
  {
    return;
  }
  if (lane == 0)
  {
    State[stateBase + 1u] = Inside(cls);
  }
  if (any(notEqual(AxisMm, vec3(0.0))))
  {
    float t = Directional(cls, lane);
    if (t < Inf)
    {
      atomicMin(State[stateBase + 2u], floatBitsToUint(t)); // reset to +infinity
    }
  }
}

// The answer this invocation works on (point x classes + class): its ceiling.
void BeginAnswer(uint answer)
{
  uvec2 ceiling = AnswerCeiling[uint(P.FirstPoint * P.Classes) + answer];
  Ceiling = min(P.RangeMm, uintBitsToFloat(ceiling.x));
  EntryEnd = ceiling.y;
}

// The least distance offered so far, or the range (or the answer's ceiling, when lower) when none
// is (the state starts at infinity). Answers do not depend on the ceiling as long as it is not
// below the answer: no pixel that gives the answer is ever cut off.
float BestSoFar(uint stateBase)
{
  return min(P.Stage == SelectTilesPerAnswer ? OwnBest : uintBitsToFloat(State[stateBase]), Ceiling);
}

// The order table's offsets start at the grid's tile nearest the tip: a tip beyond the grid (or
// any --range) needs no longer table than the grid is wide, and every tile within reach of the
// tip is within the same reach of that tile.
ivec2 CentreTile()
{
  return ivec2(clamp(floor(Tip.xy / 8.0), vec2(0.0), vec2(P.TilesX - 1, P.TilesY - 1)));
}

// The least distance from any tip of the centre tile to a tile offset by these many tiles of
// edgePx pixels along x and y (the order tables are sorted by it), lowered below its rounding.
float GapMm(ivec2 offset, int edgePx)
{
  ivec2 gap = max(abs(offset) - 1, ivec2(0));
  float mm = sqrt(float(gap.x * gap.x + gap.y * gap.y)) * float(edgePx) * P.PixelMm;
  return mm - mm * 1e-5;
}

// The least distance from the tip to a box of edgePx x edgePx pixels from firstPixel, between
// slices lo and hi (a tile's or a coarse tile's occupied slices): no cell in it is nearer.
float BoxGapMm(ivec2 firstPixel, int edgePx, float lo, float hi)
{
  vec2 corner = vec2(firstPixel);
  float dx = AxisGap(Tip.x, corner.x, corner.x + float(edgePx)) * P.PixelMm;
  float dy = AxisGap(Tip.y, corner.y, corner.y + float(edgePx)) * P.PixelMm;
  float dz = AxisGap(Tip.z, floor(lo), floor(hi) + 1.0) * P.SliceMm;
  return sqrt(dx * dx + dy * dy + dz * dz);
}

// At least the distance from the tip to one of the tile's occupied cells, as PixelDistance
// measures it: the nearer of the cells its tile range names (the lowest occupied slice, in the
// column that has it, and the highest), each occupied in a column PixelDistance reads, so no less
// than that column's distance. Raised above the rounding of either.
float TileCeilingMm(ivec2 tile, uint codeLo, uint codeHi)
{
  float best = Inf;
  for (int k = 0; k < 2; ++k)
  {
    uint code = k == 0 ? codeLo : codeHi;
    ivec2 pix = tile * 8 + ivec2(code & 7u, (code >> 3) & 7u);
    float slice = float(code >> TilePixelBits);
    float dx = AxisGap(Tip.x, float(pix.x), float(pix.x + 1)) * P.PixelMm;
    float dy = AxisGap(Tip.y, float(pix.y), float(pix.y + 1)) * P.PixelMm;
    float dz = AxisGap(Tip.z, slice, slice + 1.0) * P.SliceMm;
    best = min(best, sqrt(dx * dx + dy * dy + dz * dz));
  }
  return best + best * 1e-5 + 1e-4;
}

// The tile of the order table's entry, or ivec2(-1) when no pixel of it can be nearer than the
// best so far (outside the grid, empty, or further than the best). A tile that may be visited
// lowers the best to its ceiling (with lower set): a distance some pixel of it gives, so no
// answer changes, and the tiles after it, nearest first, are held to what the nearest tiles
// already promise rather than to the host's coarse ceiling (at 0.1 mm cells a tile is 0.8 mm
// across, and the blocks' bound 5.5 mm above the truth would leave hundreds to visit).
ivec2 TileToVisit(uint cls, uint stateBase, uint entry, bool lower)
{
  if (entry >= EntryEnd)
  {
    return ivec2(-1);
  }
  ivec2 tile = CentreTile() + Order[entry];
  if (tile.x < 0 || tile.y < 0 || tile.x >= P.TilesX || tile.y >= P.TilesY)
  {
    return ivec2(-1);
  }
  uint t = 2u * (cls * uint(P.TilesX * P.TilesY) + uint(tile.y * P.TilesX + tile.x));
  uint codeLo = TileRange[t];
  uint codeHi = TileRange[t + 1u];
  if (codeLo > codeHi)
  {
    return ivec2(-1); // empty tile
  }
  float best = BestSoFar(stateBase);
  if (BoxGapMm(tile * 8, 8, float(codeLo >> TilePixelBits), float(codeHi >> TilePixelBits)) > best)
  {
    return ivec2(-1);
  }
  if (lower)
  {
    float ceiling = TileCeilingMm(tile, codeLo, codeHi);
    if (ceiling < best)
    {
      if (P.Stage == SelectTilesPerAnswer)
      {
        OwnBest = ceiling;
      }
      else
      {
        atomicMin(State[stateBase], floatBitsToUint(ceiling));
      }
    }
  }
  return tile;
}

// The distance from the tip to the nearest occupied cell of pixel pix, when it can be at most
// best (Inf otherwise: an empty column, or one further than best); depth receives that cell's
// point nearest the tip. The answer does not depend on best once best is at least the
// distance: a larger best only lets the search look further.
float PixelDistance(uint cls, ivec2 pix, float best, out float depth)
{
  depth = 0.0;
  if (pix.x >= P.Nx || pix.y >= P.Ny)
  {
    return Inf;
  }
  uint pixels = uint(P.Nx * P.Ny);
  uint pixel = uint(pix.y * P.Nx + pix.x);
  uint r = cls * pixels + pixel;
  float zlo = uintBitsToFloat(DepthRange[r]);
  float zhi = uintBitsToFloat(DepthRange[P.RangeStride + r]);
  if (zlo > zhi)
  {
    return Inf; // nothing in this column
  }
  // The column's occupied slices span [floor(zlo), floor(zhi) + 1).
  zlo = floor(zlo);
  zhi = floor(zhi) + 1.0;
  float dx = AxisGap(Tip.x, float(pix.x), float(pix.x + 1)) * P.PixelMm;
  float dy = AxisGap(Tip.y, float(pix.y), float(pix.y + 1)) * P.PixelMm;
  float dxy2 = dx * dx + dy * dy;
  float dzColumn = AxisGap(Tip.z, zlo, zhi) * P.SliceMm;
  float lowerBound = sqrt(dxy2 + dzColumn * dzColumn);
  if (lowerBound > best)
  {
    return Inf;
  }
  if (P.PaperMode != 0)
  {
    // The paper: one cuboid from the nearest to the farthest depth.
    depth = clamp(Tip.z, zlo, zhi);
    return lowerBound;
  }
  float window = sqrt(max(0.0, best * best - dxy2)) / P.SliceMm;
  float dz = NearestSlice(ColumnBase(cls, pixel, uint(P.Words), pixels), window, depth);
  if (dz < Inf)
  {
    dz *= P.SliceMm;
    return sqrt(dxy2 + dz * dz);
  }
  return Inf;
}

// Stage SelectTiles: the entry's tile goes on the list when it has to be visited. The best so far
// only falls after this, so a tile left off could not have given the answer.
void SelectTile(uint cls, uint answer, uint stateBase, uint entry)
{
  if (TileToVisit(cls, stateBase, entry, true).x < 0)
  {
    return;
  }
  uint item = atomicAdd(ListSize[0], 1u);
  ListedTile[item] = uvec2(answer, entry);
  if (item % uint(P.TilesPerGroup) == 0u)
  {
    uint group = item / uint(P.TilesPerGroup); // the first tile of a workgroup
    atomicMax(ListSize[1], min(group + 1u, ListRowGroups));
    atomicMax(ListSize[2], group / ListRowGroups + 1u);
  }
}

// Stage SelectTiles, coarse entry c of an answer whose order table entries first..end are its
// own: when the coarse tile can hold a cell nearer than the best, each of its tiles is selected
// (SelectTile tests it). False when c and every coarse entry after it are farther than the best.
bool SelectCoarseTile(uint cls, uint answer, uint stateBase, uint c, uint first, uint end)
{
  if (GapMm(CoarseOffset[c], 8 * CoarseTiles) > BestSoFar(stateBase))
  {
    return false;
  }
  ivec2 centre = CentreTile();
  ivec2 coarse = centre / CoarseTiles + CoarseOffset[c];
  ivec2 across = (ivec2(P.TilesX, P.TilesY) + CoarseTiles - 1) / CoarseTiles;
  if (any(lessThan(coarse, ivec2(0))) || any(greaterThanEqual(coarse, across)))
  {
    return true;
  }
  uint fineWords = 2u * uint(P.Classes * P.TilesX * P.TilesY);
  uint t = fineWords + 2u * (cls * uint(across.x * across.y) + uint(coarse.y * across.x + coarse.x));
  uint codeLo = TileRange[t];
  uint codeHi = TileRange[t + 1u];
  if (codeLo > codeHi)
  {
    return true; // empty
  }
  float lo = float(codeLo >> CoarsePixelBits);
  float hi = float(codeHi >> CoarsePixelBits);
  // Its box holds every box of its tiles: no tile of it is nearer than the box.
  if (BoxGapMm(coarse * (8 * CoarseTiles), 8 * CoarseTiles, lo, hi) > BestSoFar(stateBase))
  {
    return true;
  }
  int width = 2 * P.OrderReach + 1;
  for (int k = 0; k < CoarseTiles * CoarseTiles; ++k)
  {
    ivec2 offset = coarse * CoarseTiles + ivec2(k % CoarseTiles, k / CoarseTiles) - centre;
    if (all(lessThanEqual(abs(offset), ivec2(P.OrderReach)))) // beyond it: beyond the range
    {
      uint entry = EntryOf[(offset.y + P.OrderReach) * width + offset.x + P.OrderReach];
      if (entry >= first && entry < end)
      {
        SelectTile(cls, answer, stateBase, entry);
      }
    }
  }
  return true;
}

// The visiting dispatch's workgroup, counted along its rows.
uint ListedGroup()
{
  return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
}

// The listed tile item: its point and class, and its entry in the order table (returned).
uint ReadListedTile(uint item, out uint point, out uint cls)
{
  uvec2 listed = ListedTile[item];
  point = listed.x / uint(P.Classes);
  cls = listed.x % uint(P.Classes);
  return listed.y;
}

// The host's listed item (stage VisitHostListedTiles): its point and class, and its entry in the
// order table or LaneItem plus a lane; false past the host's count.
bool ReadHostListedItem(uint item, out uint entry, out uint point, out uint cls)
{
  uint base = uint(P.FirstPoint) * HostListItemsPerPoint;
  entry = 0u;
  point = 0u;
  cls = 0u;
  if (item >= HostItem[base].x)
  {
    return false;
  }
  uvec2 listed = HostItem[base + 1u + item];
  point = listed.x / uint(P.Classes);
  cls = listed.x % uint(P.Classes);
  entry = listed.y;
  return true;
}

// A tile's record with a distance: written, and offered to its answer's choice. A record
// without one is neither written nor read.
void WriteRecord(uint answer, uint entry, float bestHere, uint bestPixel, float bestDepth)
{
  if (bestHere < Inf)
  {
    Record[answer * uint(P.OrderCount) + entry] = uvec4(floatBitsToUint(bestHere), bestPixel, floatBitsToUint(bestDepth), 0u);
    atomicMin(Choice[answer], (uint64_t(floatBitsToUint(bestHere)) << 32) | uint64_t(entry));
  }
}

// A distance that is at most the best so far lowers the best and raises its distance bit.
void Offer(uint stateBase, float d)
{
  atomicMin(State[stateBase], floatBitsToUint(d));
  if (P.Bins > 0)
  {
    int bin = int(floor((d + P.HalfDiagonalMm) / P.BinWidthMm));
    if (bin < P.Bins)
    {
      atomicOr(State[stateBase + 8u + uint(bin >> 5)], 1u << uint(bin & 31));
    }
  }
}

