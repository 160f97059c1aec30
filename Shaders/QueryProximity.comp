#version 450
// Per-query pass over the cached depth layers: one invocation per 8 x 8 tile of pixels within
// range of the tip, tiles taken nearest first (the order table). Each pixel gives
// the distance from the tip to its nearest occupied cell, a lower bound of the distance to the
// surface that is off by at most one cell diagonal; the smallest over all pixels, per class, is
// the answer. A running best per class (atomicMin on the float's bits) lets far tiles and pixels
// skip their work, which keeps the cost to the pixels near the vessel nearest the tip.
// The DirectionalLanes invocations before the tiles of the last dispatch (LaneSlots) answer "is
// the tip inside" and the directional distance, each walking its share of the axis (one lane on a
// CPU device); the dispatch's size after them follows the answers' ceilings. A dispatch answers a
// batch of points (workgroup z: the point), each with its own state and records; a 64-bit minimum
// picks each answer's record as the tiles offer theirs, and ReduceProximity.comp hands it to the
// host.
// Stage SelectTiles lists the tiles that have to be visited (and runs the lanes), and stage
// VisitListedTiles visits those (see TileList in QueryProximityCommon.glsl); stage
// VisitHostListedTiles visits the tiles and runs the lanes the host listed (HostTileList).
// No shared memory and no barriers: lavapipe runs a workgroup with a barrier as coroutines, which
// cost more than the whole query.
#extension GL_GOOGLE_include_directive : require
#include "QueryProximityCommon.glsl"

layout(local_size_x = 64) in;

// Stage SelectTilesPerAnswer: one invocation lists one answer's tiles, its lanes first, then its
// coarse tiles nearest first until they lie beyond the best: each tile it may visit lowers the
// best (in a register) before the next is tested, where SelectTiles' 64 invocations an answer
// test theirs at once against the ceiling the answer started from.
void SelectAnswerTiles(uint answer)
{
  uint point = answer / uint(P.Classes);
  uint cls = answer % uint(P.Classes);
  BeginPoint(point);
  BeginAnswer(answer);
  uint stateBase = answer * StateStride;
  for (int lane = 0; lane < P.DirectionalLanes; ++lane)
  {
    AnswerLane(cls, stateBase, lane);
  }
  uint end = min(uint(P.EndEntry), EntryEnd);
  for (uint c = 0u; c < uint(P.CoarseCount); ++c)
  {
    if (!SelectCoarseTile(cls, answer, stateBase, c, uint(P.FirstEntry), end))
    {
      break;
    }
  }
  if (OwnBest < Inf)
  {
    atomicMin(State[stateBase], floatBitsToUint(OwnBest));
  }
}

void main()
{
  if (P.Stage == SelectTilesPerAnswer)
  {
    if (gl_GlobalInvocationID.x < uint(P.AnswerCount))
    {
      SelectAnswerTiles(gl_GlobalInvocationID.x);
    }
    return;
  }
  uint slot = gl_GlobalInvocationID.x;
  uint cls = gl_WorkGroupID.y;
  uint point = gl_WorkGroupID.z;
  uint index = 0u;
  if (P.Stage == VisitListedTiles)
  {
    slot = ListedGroup() * 64u + gl_LocalInvocationID.x;
    if (slot >= ListSize[0])
    {
      return;
    }
    index = ReadListedTile(slot, point, cls);
  }
  else if (P.Stage == VisitHostListedTiles)
  {
    if (!ReadHostListedItem(slot, index, point, cls))
    {
      return;
    }
  }
  else if (P.Stage == VisitOrderedTiles)
  {
    // The dispatch's first LaneSlots invocations are the lanes, the rest its tiles.
    index = slot - uint(P.LaneSlots) + uint(P.FirstEntry);
    if (slot >= uint(P.LaneSlots) && index >= uint(P.EndEntry))
    {
      return;
    }
  }
  BeginPoint(point);
  uint answer = point * uint(P.Classes) + cls;
  uint stateBase = answer * StateStride;
  BeginAnswer(answer);
  if (P.Stage == SelectTiles)
  {
    // The answer's workgroups (gl_NumWorkGroups.x of them: one for a batch, where the answers
    // fill the device) share its lanes and the coarse tiles over its entries up to its own end:
    // lavapipe pays for every workgroup it starts, and a dispatch as far as the batch's highest
    // ceiling started thousands per tip that had nothing to do.
    uint stride = gl_NumWorkGroups.x * 64u;
    for (uint lane = slot; lane < uint(P.DirectionalLanes); lane += stride)
    {
      AnswerLane(cls, stateBase, int(lane));
    }
    uint end = min(uint(P.EndEntry), EntryEnd);
    for (uint c = slot; c < uint(P.CoarseCount); c += stride)
    {
      if (!SelectCoarseTile(cls, answer, stateBase, c, uint(P.FirstEntry), end))
      {
        break;
      }
    }
    return;
  }
  if (P.Stage == VisitOrderedTiles && slot < uint(P.LaneSlots))
  {
    AnswerLane(cls, stateBase, int(slot));
    return;
  }
  if (P.Stage == VisitHostListedTiles && index >= LaneItem)
  {
    AnswerLane(cls, stateBase, int(index - LaneItem));
    return;
  }
  ivec2 tile = TileToVisit(cls, stateBase, index, true);
  if (tile.x < 0)
  {
    return;
  }
  // The tile's record: its least distance, and the last of its pixels that gives it.
  float bestHere = Inf;
  uint bestPixel = 0u;
  float bestDepth = 0.0;
  for (int k = 0; k < 64; ++k)
  {
    ivec2 pix = tile * 8 + ivec2(k & 7, k >> 3);
    float best = min(bestHere, BestSoFar(stateBase));
    float depth;
    float d = PixelDistance(cls, pix, best, depth);
    if (d <= best)
    {
      bestHere = d;
      bestPixel = uint(pix.y * P.Nx + pix.x);
      bestDepth = depth;
      Offer(stateBase, d);
    }
  }
  WriteRecord(answer, index, bestHere, bestPixel, bestDepth);
}
