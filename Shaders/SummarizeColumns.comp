#version 450
// Per pixel column, the lowest and highest occupied slice, read from the occupancy bits. The
// rasteriser used to keep these with two atomics per pixel it touched; deriving them once per
// column afterwards gives the same slices and makes re-rendering a quarter faster on lavapipe,
// where every atomic (and the read that guards it) is a scalar loop over the SIMD lanes.
#extension GL_GOOGLE_include_directive : require
#include "DepthLayersCommon.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Occupancy { uint Occupied[]; };
layout(std430, binding = 1) writeonly buffer DepthRanges { uint DepthRange[]; };

layout(push_constant) uniform Parameters
{
  uint Pixels;      // of one class
  uint Classes;
  uint Words;       // per column
  uint RangeStride; // classes x pixels: the farthest slices follow the nearest ones
} P;

void main()
{
  uint id = gl_GlobalInvocationID.x;
  if (id >= P.Pixels * P.Classes)
  {
    return;
  }
  uint base = ColumnBase(id / P.Pixels, id % P.Pixels, P.Words, P.Pixels);
  int first = -1;
  int last = -1;
  for (uint w = 0u; w < P.Words; ++w)
  {
    uint bits = Occupied[base + w];
    if (bits != 0u)
    {
      if (first < 0)
      {
        first = int(w) * 32 + findLSB(bits);
      }
      last = int(w) * 32 + findMSB(bits);
    }
  }
  // Slices as floats, so that float order is uint order; an empty column has lo > hi.
  DepthRange[id] = first < 0 ? 0x7F800000u : floatBitsToUint(float(first));
  DepthRange[P.RangeStride + id] = first < 0 ? 0u : floatBitsToUint(float(last));
}
