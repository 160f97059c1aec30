#version 450
// Per 8 x 8 tile of pixels, the lowest and highest occupied depth: lets a query skip a whole tile
// with one read when it is empty or further than the best distance found so far.
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
  for (int j = ty * 8; j < min(ty * 8 + 8, P.Ny); ++j)
  {
    for (int i = tx * 8; i < min(tx * 8 + 8, P.Nx); ++i)
    {
      uint r = cls * pixels + uint(j * P.Nx + i);
      lo = min(lo, DepthRange[r]);
      hi = max(hi, DepthRange[P.RangeStride + r]);
    }
  }
  TileRange[2u * id] = lo;
  TileRange[2u * id + 1u] = hi;
}
