#version 450
// Per tile of TilePx x TilePx pixels, the lowest and highest occupied depth: lets a query skip a
// whole tile with one read when it is empty or further than the best distance found so far. Run
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
  uint lo = 0x7F800000u; // +inf: empty
  uint hi = 0u;
  uint pixels = uint(P.Nx * P.Ny);
  for (int j = ty * P.TilePx; j < min(ty * P.TilePx + P.TilePx, P.Ny); ++j)
  {
    for (int i = tx * P.TilePx; i < min(tx * P.TilePx + P.TilePx, P.Nx); ++i)
    {
      uint r = cls * pixels + uint(j * P.Nx + i);
      lo = min(lo, DepthRange[r]);
      hi = max(hi, DepthRange[P.RangeStride + r]);
    }
  }
  TileRange[P.Offset + 2u * id] = lo;
  TileRange[P.Offset + 2u * id + 1u] = hi;
}
