#ifndef vpImageComparison_h
#define vpImageComparison_h

#include <string>

namespace vp
{
/// How two RGB pictures differ, for image regression tests.
struct ImageDifference
{
  bool SameSize = false;
  /// Pixels whose largest channel difference exceeds the threshold, as a fraction of all.
  double FractionDifferent = 1.0;
  /// Mean absolute channel difference over all pixels and channels (0..255).
  double MeanAbsDifference = 255.0;
};

/// Compares two PNG files. A pixel counts as different when a channel differs by more than
/// thresholdLevels (default 32 of 255: antialiasing and driver rounding stay below, a changed
/// colour does not). When differenceFile is not empty, a picture of the differences (white where
/// different, the baseline dimmed elsewhere) is written there. A missing or unreadable file gives
/// SameSize false.
ImageDifference CompareImages(const std::string& actualFile, const std::string& baselineFile,
  const std::string& differenceFile, int thresholdLevels = 32);
} // namespace vp

#endif
