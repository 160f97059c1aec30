#version 450
// Per tile of TilePx x TilePx pixels, the lowest and highest occupied depth: lets a query skip a
// whole tile with one read when it is empty or further than the best distance found so far. Each
// comes with the pixel whose column has it, so that a tile the query may visit promises a cell at
// a known place (TileCeilingMm in QueryProximityCommon.glsl): the tile's farthest column, which
// it promised before, left some 8 % more tiles listed per tip (17.3 -> 16.0 on IRCADb patient 1). Run
// for the 8 x 8 tiles the query visits and again for coarse tiles of 4 x 4 of them, which the
// listing walks first (QueryProximityCommon.glsl), written after the fine ones (Offset).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer DepthRanges { uint DepthRange[]; };
layout(std430, binding = 1) writeonly buffer TileRanges { uint TileRange[]; };

layout(push_constant) uniform Parameters
{
  int Nx;
  int Ny;
  int TilesX;
  int TilesY;
  uint Classes;
  uint RangeStride;
  int TilePx;
  uint Offset; // words before this level's tiles
} P;

void main()
{
  uint tiles = uint(P.TilesX * P.TilesY);
  uint id = gl_GlobalInvocationID.x;
  if (id >= tiles * P.Classes)
  {
    return;
  }
  uint cls = id / tiles;
  uint tile = id % tiles;
  int tx = int(tile) % P.TilesX;
  int ty = int(tile) / P.TilesX;
  // The slice above the bits that say which of the tile's pixels holds it (row by row from the
  // tile's first; 10 bits at most, above 2^20 slices at most: vp::DepthLayerGrid): min and max
  // then give the extreme slices and a column that has each.
  uint pixelBits = uint(findMSB(P.TilePx * P.TilePx));
  uint lo = 0xFFFFFFFFu; // empty: lo > hi
  uint hi = 0u;
  uint pixels = uint(P.Nx * P.Ny);
  for (int j = ty * P.TilePx; j < min(ty * P.TilePx + P.TilePx, P.Ny); ++j)
  {
    for (int i = tx * P.TilePx; i < min(tx * P.TilePx + P.TilePx, P.Nx); ++i)
    {
      uint r = cls * pixels + uint(j * P.Nx + i);
      float zlo = uintBitsToFloat(DepthRange[r]);
      float zhi = uintBitsToFloat(DepthRange[P.RangeStride + r]);
      if (zlo <= zhi)
      {
        uint local = uint((j - ty * P.TilePx) * P.TilePx + (i - tx * P.TilePx));
        lo = min(lo, (uint(zlo) << pixelBits) | local);
        hi = max(hi, (uint(zhi) << pixelBits) | local);
      }
    }
  }
  TileRange[P.Offset + 2u * id] = lo;
  TileRange[P.Offset + 2u * id + 1u] = hi;
}
