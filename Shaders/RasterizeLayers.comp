#version 450
// Conservative orthographic rasterisation of one vessel class into its depth layers: one
// invocation per triangle. Every pixel whose footprint the triangle touches gets the exact depth
// range of the triangle over that footprint (the triangle clipped to the pixel square), so a
// vessel thinner than a pixel, or a triangle between pixel centres, still leaves its mark; this is
// what hardware conservative rasterisation would give, which lavapipe does not have.
#extension GL_GOOGLE_include_directive : require
#include "DepthLayersCommon.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Positions { float Position[]; };
layout(std430, binding = 1) readonly buffer Indices { uint Index[]; };
layout(std430, binding = 2) buffer Occupancy { uint Occupied[]; };
layout(std430, binding = 3) buffer Crossings { uint Crossing[]; };
// Where in its slice the crossing lies, in quarters (a slice with one crossing: its parity bits
// are the quarter's two bits; the penetration's volume places the wall by them).
layout(std430, binding = 4) buffer CrossingHalves { uint CrossingHalf[]; };
layout(std430, binding = 5) buffer CrossingQuarters { uint CrossingQuarter[]; };

layout(push_constant) uniform Parameters
{
  vec3 Origin;        // box corner, relative to the uploaded positions' anchor (mm)
  float InvPixelMm;
  float InvSliceMm;
  int Nx;
  int Ny;
  int Nz;
  int Words;
  uint Class;
  uint FirstTriangle;
  uint TriangleCount;
} P;

// Coverage tolerance in cells: surfaces within it of a cell mark the cell. It absorbs float
// rounding of the grid coordinates and is part of the engine's error bound.
const float Eps = 1.0e-3;

vec3 Vertex(uint i)
{
  vec3 p = vec3(Position[3 * i], Position[3 * i + 1], Position[3 * i + 2]);
  return vec3((p.xy - P.Origin.xy) * P.InvPixelMm, (p.z - P.Origin.z) * P.InvSliceMm);
}

void Extend(inout float wmin, inout float wmax, float w)
{
  wmin = min(wmin, w);
  wmax = max(wmax, w);
}

// Clips the edge p-q to the square lo-hi in (u, v) (Liang-Barsky) and extends the depth range by
// the depths at the clipped ends. The clipped triangle's corners are these ends and the square's
// corners inside the triangle; the depth, linear over the triangle, is extreme at its corners.
// (Clipping a polygon through local arrays costs lavapipe thirty times more.)
bool ClipEdge(vec3 p, vec3 q, vec2 lo, vec2 hi, inout float wmin, inout float wmax)
{
  vec3 d = q - p;
  float t0 = 0.0;
  float t1 = 1.0;
  if (d.x == 0.0)
  {
    if (p.x < lo.x || p.x > hi.x) return false;
  }
  else
  {
    float ta = (lo.x - p.x) / d.x;
    float tb = (hi.x - p.x) / d.x;
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  if (d.y == 0.0)
  {
    if (p.y < lo.y || p.y > hi.y) return false;
  }
  else
  {
    float ta = (lo.y - p.y) / d.y;
    float tb = (hi.y - p.y) / d.y;
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  if (t0 > t1)
  {
    return false;
  }
  Extend(wmin, wmax, p.z + t0 * d.z);
  Extend(wmin, wmax, p.z + t1 * d.z);
  return true;
}

// Edge function with exact antisymmetry: E(a, b, p) == -E(b, a, p) bit for bit, so a pixel centre
// on an edge shared by two triangles is claimed by exactly one of them (with the tie rule below).
float EdgeFunction(vec2 a, vec2 b, vec2 p)
{
  bool swapped = a.x > b.x || (a.x == b.x && a.y > b.y);
  vec2 s = swapped ? b : a;
  vec2 e = swapped ? a : b;
  precise float v = (e.x - s.x) * (p.y - s.y) - (e.y - s.y) * (p.x - s.x);
  return swapped ? -v : v;
}

// Tie rule for centres exactly on an edge: of the two directions of an edge, exactly one owns it.
bool OwnsEdge(vec2 a, vec2 b)
{
  vec2 d = b - a;
  return d.y < 0.0 || (d.y == 0.0 && d.x > 0.0);
}

bool Covers(float e, vec2 a, vec2 b)
{
  return e > 0.0 || (e == 0.0 && OwnsEdge(a, b));
}

void SetBits(uint base, int first, int last)
{
  int w0 = first >> 5;
  int w1 = last >> 5;
  for (int w = w0; w <= w1; ++w)
  {
    uint lo = (w == w0) ? uint(first & 31) : 0u;
    uint hi = (w == w1) ? uint(last & 31) : 31u;
    uint mask = (hi == 31u ? 0xFFFFFFFFu : ((1u << (hi + 1u)) - 1u)) & ~((1u << lo) - 1u);
    // Most cells of a dense mesh are marked many times over; reading first spares the atomics.
    if ((Occupied[base + uint(w)] & mask) != mask)
    {
      atomicOr(Occupied[base + uint(w)], mask);
    }
  }
}

void main()
{
  uint t = gl_GlobalInvocationID.x;
  if (t >= P.TriangleCount)
  {
    return;
  }
  uint tri = (P.FirstTriangle + t) * 3u;
  vec3 g0 = Vertex(Index[tri]);
  vec3 g1 = Vertex(Index[tri + 1u]);
  vec3 g2 = Vertex(Index[tri + 2u]);
  vec3 lo = min(min(g0, g1), g2);
  vec3 hi = max(max(g0, g1), g2);
  // Triangles below the box are kept: their crossings count for the inside test above them.
  if (hi.x < -Eps || hi.y < -Eps || lo.x > float(P.Nx) + Eps || lo.y > float(P.Ny) + Eps || lo.z > float(P.Nz) + Eps)
  {
    return;
  }
  int i0 = max(0, int(floor(lo.x - Eps)));
  int i1 = min(P.Nx - 1, int(floor(hi.x + Eps)));
  int j0 = max(0, int(floor(lo.y - Eps)));
  int j1 = min(P.Ny - 1, int(floor(hi.y + Eps)));
  uint pixels = uint(P.Nx * P.Ny);

  // Orientation-free centre test: make the triangle counter-clockwise in (u, v).
  vec2 a = g0.xy;
  vec2 b = g1.xy;
  vec2 c = g2.xy;
  float wa = g0.z;
  float wb = g1.z;
  float wc = g2.z;
  float area = EdgeFunction(a, b, c);
  if (area < 0.0)
  {
    vec2 tv = b; b = c; c = tv;
    float tw = wb; wb = wc; wc = tw;
    area = -area;
  }

  // One flat loop over the bounding box: nested loops with per-lane bounds cost lavapipe a
  // quarter more.
  int count = (i1 - i0 + 1) * (j1 - j0 + 1);
  int i = i0 - 1;
  int j = j0;
  for (int k = 0; k < count; ++k)
  {
    {
      if (++i > i1)
      {
        i = i0;
        ++j;
      }
      uint pixel = uint(j * P.Nx + i);
      uint base = ColumnBase(P.Class, pixel, uint(P.Words), pixels);

      if (area > 0.0)
      {
        vec2 centre = vec2(float(i) + 0.5, float(j) + 0.5);
        float ea = EdgeFunction(b, c, centre);
        float eb = EdgeFunction(c, a, centre);
        float ec = EdgeFunction(a, b, centre);
        if (Covers(ea, b, c) && Covers(eb, c, a) && Covers(ec, a, b))
        {
          float w = (ea * wa + eb * wb + ec * wc) / area;
          if (w < float(P.Nz))
          {
            int s = clamp(int(floor(w)), 0, P.Nz - 1);
            uint word = base + uint(s >> 5);
            uint bit = 1u << uint(s & 31);
            atomicXor(Crossing[word], bit);
            int quarter = clamp(int(floor((w - float(s)) * 4.0)), 0, 3);
            if ((quarter & 2) != 0)
            {
              atomicXor(CrossingHalf[word], bit);
            }
            if ((quarter & 1) != 0)
            {
              atomicXor(CrossingQuarter[word], bit);
            }
          }
        }
      }

      float wmin;
      float wmax;
      if (i0 == i1 && j0 == j1)
      {
        wmin = lo.z;
        wmax = hi.z;
      }
      else
      {
        vec2 sqLo = vec2(float(i), float(j)) - Eps;
        vec2 sqHi = vec2(float(i + 1), float(j + 1)) + Eps;
        wmin = uintBitsToFloat(0x7F800000u);
        wmax = -wmin;
        bool hit = ClipEdge(g0, g1, sqLo, sqHi, wmin, wmax);
        hit = ClipEdge(g1, g2, sqLo, sqHi, wmin, wmax) || hit;
        hit = ClipEdge(g2, g0, sqLo, sqHi, wmin, wmax) || hit;
        if (area > 0.0)
        {
          for (int k = 0; k < 4; ++k)
          {
            vec2 corner = vec2((k & 1) != 0 ? sqHi.x : sqLo.x, (k & 2) != 0 ? sqHi.y : sqLo.y);
            float ea = EdgeFunction(b, c, corner);
            float eb = EdgeFunction(c, a, corner);
            float ec = EdgeFunction(a, b, corner);
            if (ea >= 0.0 && eb >= 0.0 && ec >= 0.0)
            {
              Extend(wmin, wmax, clamp((ea * wa + eb * wb + ec * wc) / area, lo.z, hi.z));
              hit = true;
            }
          }
        }
        if (!hit)
        {
          continue;
        }
      }
      wmin -= Eps;
      wmax += Eps;
      if (wmax < 0.0 || wmin >= float(P.Nz))
      {
        continue;
      }
      wmin = max(wmin, 0.0);
      wmax = min(wmax, float(P.Nz) - 0.5);
      SetBits(base, int(wmin), int(wmax));
    }
  }
}
