#ifndef vpModelsBenchmark_h
#define vpModelsBenchmark_h

#include "vpBenchmarkSupport.h"

#include <string>

namespace vp
{
/// A patient's label series made longer: a 260-slice patient from a 129-slice one.
struct ModelsBenchSettings
{
  /// A folder of DICOM label series, one per structure (IRCADb's MASKS_DICOM), or one series.
  std::string Input;
  /// How many times each series is laid end to end along its slices' normal (1: as it is).
  int Copies = 2;
  /// Runs of each build; the median and p95 are over them.
  int Runs = 5;
  /// Where the longer series are written (removed afterwards).
  std::string WorkFolder;
};

/// Writes each series under input that the built-in label table places (or input itself when it
/// is one series) copies times end to end along its normal into output/<structure>: every file
/// again, moved by the series' length per copy, with its own SOPInstanceUID. The files keep their
/// transfer syntax and pixels, so reading them costs what reading a longer scan would. Returns
/// the number of slices a series has afterwards.
int StackDicomSeries(const std::string& input, const std::string& output, int copies);

/// BuildVesselModels on the input as it is and on it stacked Copies times, Runs each: the read,
/// each class's build and the total, median and p95, with each class's voxels, triangles and
/// volume (the stacked classes must hold Copies times the voxels: "voxels_match").
BenchJson BenchModels(const ModelsBenchSettings& settings);
} // namespace vp

#endif
