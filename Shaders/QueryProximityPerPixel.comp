#version 450
// The query pass of QueryProximity.comp for GPUs: one invocation per pixel, the paper's "one
// thread per pixel", a workgroup per 8 x 8 tile of the order table. The per-tile pass walks a
// tile's 64 pixels in one invocation, each pixel a chain of dependent memory reads: on a GPU
// that chain, not the number of pixels, was the query's time. Here the 64 pixels of a tile are
// read side by side, and the workgroup then picks the tile's record as the per-tile pass does:
// the least distance, and the last pixel (in the tile's order) that gives it.
//
// The answers are the per-tile pass's, bit for bit. Only a record holding the answer's best
// distance can be chosen, and such a record is the same in both passes:
// a pixel that gives the best distance is never cut off by the running best (which is never
// below it) and its distance does not depend on how far the search looked; every pixel of the
// tile with that distance is offered, and the last wins. The distance bits are the same too: the
// best distance's bit is raised in both, and the host reads only the first raised bit.
// It visits the order table's tiles (stage VisitOrderedTiles), the tiles a batch listed
// (VisitListedTiles; the per-tile pass lists them) or those the host listed (VisitHostListedTiles).
// Shared memory and barriers: fine on a GPU; lavapipe uses the per-tile pass.
#extension GL_GOOGLE_include_directive : require
#include "QueryProximityCommon.glsl"

layout(local_size_x = 64) in;

shared float CandidateMm[64];
shared float CandidateDepth[64];

void main()
{
  uint k = gl_LocalInvocationID.x;
  uint cls = gl_WorkGroupID.y;
  uint point = gl_WorkGroupID.z;
  uint group = gl_WorkGroupID.x;
  uint entry;
  if (P.Stage == VisitListedTiles)
  {
    // One workgroup per listed tile (the last row of the dispatch may run past them: all of a
    // workgroup leaves together, before its barrier).
    group = ListedGroup();
    if (group >= ListSize[0])
    {
      return;
    }
    entry = ReadListedTile(group, point, cls);
  }
  else if (P.Stage == VisitHostListedTiles)
  {
    // One workgroup per item the host listed, the dispatch as long as its count.
    if (!ReadHostListedItem(group, entry, point, cls))
    {
      return;
    }
  }
  else
  {
    entry = group - uint(P.LaneSlots) + uint(P.FirstEntry); // this dispatch's workgroups end it
  }
  BeginPoint(point);
  uint answer = point * uint(P.Classes) + cls;
  uint stateBase = answer * StateStride;
  if (P.Stage == VisitOrderedTiles && group < uint(P.LaneSlots))
  {
    // The dispatch's first workgroups: the lanes of "inside" and the directional walk.
    AnswerLane(cls, stateBase, int(group * 64u + k));
    return;
  }
  if (P.Stage == VisitHostListedTiles && entry >= LaneItem)
  {
    AnswerLane(cls, stateBase, int((entry - LaneItem) * 64u + k));
    return;
  }
  BeginAnswer(answer);
  ivec2 tile = TileToVisit(cls, stateBase, entry, k == 0u); // one lowering per tile
  float d = Inf;
  float depth = 0.0;
  if (tile.x >= 0)
  {
    ivec2 pix = tile * 8 + ivec2(int(k & 7u), int(k >> 3u));
    float best = BestSoFar(stateBase);
    d = PixelDistance(cls, pix, best, depth);
    if (d <= best)
    {
      Offer(stateBase, d);
    }
    else
    {
      d = Inf;
    }
  }
  CandidateMm[k] = d;
  CandidateDepth[k] = depth;
  barrier();
  if (k == 0u)
  {
    if (tile.x < 0)
    {
      return;
    }
    float bestHere = Inf;
    uint bestK = 0u;
    for (uint j = 0u; j < 64u; ++j)
    {
      if (CandidateMm[j] <= bestHere && CandidateMm[j] < Inf)
      {
        bestHere = CandidateMm[j];
        bestK = j;
      }
    }
    ivec2 pix = tile * 8 + ivec2(int(bestK & 7u), int(bestK >> 3u));
    WriteRecord(answer, entry, bestHere, uint(pix.y * P.Nx + pix.x), CandidateDepth[bestK]); // none when Inf
  }
}
