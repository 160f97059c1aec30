#version 450
// The query pass for batches on a GPU: one invocation per answer (point x class), walking the
// tiles near its tip one after another, nearest coarse tile first, with its own running best in
// a register. The other passes spread one answer over many invocations (a tile or a pixel each)
// that share the best through atomics and, in a batch, a list of tiles written by one stage and
// read by the next: at 4,096 tips a submission took some 20 ms of an H100's time, 5 us a tip,
// where thousands of tips side by side fill the device without splitting any of them.
//
// The answers are the other passes', bit for bit: the walk looks at the tiles the listing would
// list (SelectCoarseTile's tests, with the best as it falls), a tile's record is the least
// distance over its pixels and the last pixel that gives it, and between tiles the least
// distance wins and, among equal ones, the lowest entry of the order table (as the 64-bit
// minimum over records picks). The running best is never below the answer's distance (it starts
// at the ceiling, falls to tile ceilings some pixel meets, and to distances found), so the pixel
// that gives the answer is never cut off. Inside and the directional distance are the lanes'
// answers, the lanes walked in order (the first that meets the surface is the nearest).
#extension GL_GOOGLE_include_directive : require
#include "QueryProximityCommon.glsl"

layout(local_size_x = 64) in;

void main()
{
  // Stage WalkAnswers: EndEntry holds the submission's answers.
  uint answer = gl_GlobalInvocationID.x;
  if (answer >= uint(P.EndEntry))
  {
    return;
  }
  uint point = answer / uint(P.Classes);
  uint cls = answer % uint(P.Classes);
  BeginPoint(point);
  BeginAnswer(answer);
  uint stateBase = answer * StateStride;

  State[stateBase + 1u] = Inside(cls);
  if (any(notEqual(AxisMm, vec3(0.0))))
  {
    for (int lane = 0; lane < P.DirectionalLanes; ++lane)
    {
      float t = Directional(cls, lane);
      if (t < Inf)
      {
        State[stateBase + 2u] = floatBitsToUint(t); // reset to +infinity
        break;
      }
    }
  }

  float best = Ceiling;
  float answerMm = Inf;
  uint answerEntry = 0xFFFFFFFFu, answerPixel = 0u;
  float answerDepth = 0.0;
  ivec2 centre = CentreTile();
  ivec2 across = (ivec2(P.TilesX, P.TilesY) + CoarseTiles - 1) / CoarseTiles;
  uint fineWords = 2u * uint(P.Classes * P.TilesX * P.TilesY);
  uint classTiles = cls * uint(P.TilesX * P.TilesY);
  int width = 2 * P.OrderReach + 1;
  for (uint c = 0u; c < uint(P.CoarseCount); ++c)
  {
    if (GapMm(CoarseOffset[c], 8 * CoarseTiles) > best)
    {
      break; // this coarse tile and every one after it are farther than the best
    }
    ivec2 coarse = centre / CoarseTiles + CoarseOffset[c];
    if (any(lessThan(coarse, ivec2(0))) || any(greaterThanEqual(coarse, across)))
    {
      continue;
    }
    uint ct = fineWords + 2u * (cls * uint(across.x * across.y) + uint(coarse.y * across.x + coarse.x));
    float coarseLo = uintBitsToFloat(TileRange[ct]);
    float coarseHi = uintBitsToFloat(TileRange[ct + 1u]);
    if (coarseLo > coarseHi || BoxGapMm(coarse * (8 * CoarseTiles), 8 * CoarseTiles, coarseLo, coarseHi) > best)
    {
      continue;
    }
    for (int k = 0; k < CoarseTiles * CoarseTiles; ++k)
    {
      ivec2 offset = coarse * CoarseTiles + ivec2(k % CoarseTiles, k / CoarseTiles) - centre;
      if (any(greaterThan(abs(offset), ivec2(P.OrderReach)))) // beyond it: beyond the range
      {
        continue;
      }
      uint entry = EntryOf[(offset.y + P.OrderReach) * width + offset.x + P.OrderReach];
      ivec2 tile = centre + offset;
      if (entry >= EntryEnd || tile.x >= P.TilesX || tile.y >= P.TilesY)
      {
        continue;
      }
      uint t = 2u * (classTiles + uint(tile.y * P.TilesX + tile.x));
      float tileLo = uintBitsToFloat(TileRange[t]);
      float tileHi = uintBitsToFloat(TileRange[t + 1u]);
      if (tileLo > tileHi || BoxGapMm(tile * 8, 8, tileLo, tileHi) > best)
      {
        continue;
      }
      best = min(best, TileCeilingMm(tile, floor(tileLo), floor(tileHi)));
      float hereMm = Inf;
      uint herePixel = 0u;
      float hereDepth = 0.0;
      for (int p = 0; p < 64; ++p)
      {
        ivec2 pix = tile * 8 + ivec2(p & 7, p >> 3);
        float limit = min(hereMm, best);
        float depth;
        float d = PixelDistance(cls, pix, limit, depth);
        if (d <= limit)
        {
          hereMm = d;
          herePixel = uint(pix.y * P.Nx + pix.x);
          hereDepth = depth;
        }
      }
      if (hereMm < answerMm || (hereMm == answerMm && hereMm < Inf && entry < answerEntry))
      {
        answerMm = hereMm;
        answerEntry = entry;
        answerPixel = herePixel;
        answerDepth = hereDepth;
      }
      best = min(best, hereMm);
    }
  }
  if (answerMm < Inf)
  {
    Offer(stateBase, answerMm);
    WriteRecord(answer, answerEntry, answerMm, answerPixel, answerDepth);
  }
}
