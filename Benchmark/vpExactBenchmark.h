#ifndef vpExactBenchmark_h
#define vpExactBenchmark_h

#include "vpBenchmarkSupport.h"

namespace vp
{
/// Per class at one mesh size: the exact engine (Embree BVH) on random tips and on a tracked tip
/// (the previous answer bounding the search; for an open surface also without its inside vote),
/// VTK's vtkStaticCellLocator on the same tips, and the paper's brute-force CPU algorithm on the
/// first bruteQueries; the speed-ups and the largest disagreements. No range cut-off: the full
/// search, like the brute-force reference. Progress on stderr.
BenchJson BenchExact(const std::vector<NamedMesh>& refined, std::size_t target, const BenchPoints& tips,
  const BenchPoints& track, int bruteQueries);
} // namespace vp

#endif
