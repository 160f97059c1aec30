#version 450
// The passes after QueryProximity.comp that keep the host out of the loop, one shader with three
// steps (Step), each a dispatch over the batch's answers (point x class):
//   0: reset each answer's state: no best distance yet (+infinity; the query takes the smaller
//      of it and its range), no inside, no directional distance, no record chosen, no distance
//      bits. Run once when the state is made: every query leaves it so (step 2).
//   1: one invocation per record: a record whose distance equals its answer's best offers its
//      index, and the lowest index wins (the record the host once found by scanning them all);
//   2: one invocation per answer: copy the state, with the chosen record's distance, pixel and
//      depth, straight into the host-visible answers, so the host reads 32 words per answer and
//      nothing else and no copy command follows, then reset the state for the next query, which
//      so needs no reset dispatch of its own.
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer QueryState { uint State[]; };
layout(std430, binding = 1) readonly buffer Records { uvec4 Record[]; };
layout(std430, binding = 2) writeonly buffer Answers { uint Answer[]; };

layout(push_constant) uniform Parameters
{
  uint Step;
  uint Answers;    // points x classes
  uint OrderCount; // records per answer
} P;

const uint StateStride = 32u;
const uint NoRecord = 0xFFFFFFFFu;
const uint Infinity = 0x7F800000u; // float bits

void Reset(uint base)
{
  State[base] = Infinity;          // no best distance yet
  State[base + 1u] = 0u;           // not inside
  State[base + 2u] = Infinity;     // no directional distance
  State[base + 3u] = NoRecord;
  for (uint w = 4u; w < StateStride; ++w)
  {
    State[base + w] = 0u;
  }
}

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (P.Step == 0u)
  {
    if (i >= P.Answers)
    {
      return;
    }
    Reset(i * StateStride);
    return;
  }
  if (P.Step == 1u)
  {
    if (i >= P.Answers * P.OrderCount)
    {
      return;
    }
    uint answer = i / P.OrderCount;
    uint base = answer * StateStride;
    if (Record[i].x == State[base] && State[base] != Infinity)
    {
      atomicMin(State[base + 3u], i - answer * P.OrderCount);
    }
    return;
  }
  if (i >= P.Answers)
  {
    return;
  }
  uint base = i * StateStride;
  uint chosen = State[base + 3u];
  for (uint w = 0u; w < StateStride; ++w)
  {
    Answer[base + w] = State[base + w];
  }
  if (chosen != NoRecord)
  {
    uvec4 r = Record[i * P.OrderCount + chosen];
    Answer[base + 4u] = r.x;
    Answer[base + 5u] = r.y;
    Answer[base + 6u] = r.z;
  }
  Reset(base);
}
