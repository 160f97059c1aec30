#version 450
// The pass after QueryProximity.comp (or its per-pixel form) that keeps the host out of the loop,
// one invocation per answer (point x class), in two steps (Step):
//   0: reset each answer's state: no best distance yet (+infinity; the query takes the smaller
//      of it and its range), no inside, no directional distance, no record chosen, no distance
//      bits. Run once when the state is made: every query leaves it so (step 1).
//   1: copy the state, with the record the query's 64-bit minimum chose (its distance, pixel and
//      depth), straight into the host-visible answers, so the host reads 32 words per answer and
//      nothing else and no copy command follows; then reset the state for the next query, which
//      so needs no reset dispatch of its own. The first answer's word 7 receives the number of
//      tiles the submission listed (0 when it listed none), for the benchmarks.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer QueryState { uint State[]; };
layout(std430, binding = 1) readonly buffer Records { uvec4 Record[]; };
layout(std430, binding = 2) writeonly buffer Answers { uint Answer[]; };
layout(std430, binding = 3) buffer Choices { uint64_t Choice[]; };
// The batch's list of tiles to visit (QueryProximityCommon.glsl): its size, and the visiting
// dispatch's workgroup counts.
layout(std430, binding = 4) buffer TileListSize { uint ListSize[]; };

layout(push_constant) uniform Parameters
{
  uint Step;
  uint Answers;    // points x classes
  uint OrderCount; // records per answer
  uint FirstAnswer; // where this submission's answers start in Answers (its slot)
} P;

const uint StateStride = 32u;
const uint NoRecord = 0xFFFFFFFFu;
const uint Infinity = 0x7F800000u; // float bits
const uint64_t NoChoice = 0xFFFFFFFFFFFFFFFFul;

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
  if (i >= P.Answers)
  {
    return;
  }
  uint base = i * StateStride;
  uint listed = 0u;
  if (i == 0u)
  {
    listed = ListSize[0];
    ListSize[0] = 0u;
    ListSize[1] = 0u; // no workgroups
    ListSize[2] = 0u;
    ListSize[3] = 1u;
  }
  if (P.Step == 1u)
  {
    uint64_t choice = Choice[i];
    uint chosen = choice == NoChoice ? NoRecord : uint(choice & 0xFFFFFFFFul);
    uint to = (P.FirstAnswer + i) * StateStride;
    for (uint w = 0u; w < StateStride; ++w)
    {
      Answer[to + w] = State[base + w];
    }
    Answer[to + 3u] = chosen;
    if (i == 0u)
    {
      Answer[to + 7u] = listed;
    }
    if (chosen != NoRecord)
    {
      uvec4 r = Record[i * P.OrderCount + chosen];
      Answer[to + 4u] = r.x;
      Answer[to + 5u] = r.y;
      Answer[to + 6u] = r.z;
    }
  }
  Reset(base);
  Choice[i] = NoChoice;
}
