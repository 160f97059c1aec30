#ifndef vpCohortManifest_h
#define vpCohortManifest_h

#include "vpPoseReading.h"

#include <string>
#include <vector>

namespace vp
{
/// One case of a cohort: a patient's segmentation and what to compute on it. Paths are as the
/// manifest gives them, taken from the manifest's folder when relative.
struct CohortCase
{
  std::string Name;         ///< the case's folder under the output: letters, digits, '.', '_', '-'
  std::string Segmentation; ///< what `models` reads: a DICOM label series folder, a SEG, NRRD, NIfTI
  std::string Poses;        ///< a tracked session, as `track --poses` reads it; empty: none
  std::string Tips;         ///< tips, as `distance --tips` reads them; empty: none
  /// The resection plan: the tumours' surfaces (each as `--tumour` takes it, `ID=FILE` or FILE),
  /// ';' between them in the cell; empty: none.
  std::vector<std::string> Plan;
  std::string Scalpel; ///< the instrument's model; empty: the built-in CUSA handpiece
  /// How the poses are read (columns pose_space, pose_units, time_units, tool, reference, as
  /// track's --pose-space, --pose-units, --time-units, --tool, --reference); an empty cell: as
  /// the pose file declares, else LPS, mm, s.
  PoseReading Reading;
  int Line = 0;        ///< the manifest's line, for messages
};

/// Whether a file name is one the cohort writes beside its cases: cohort.csv, cohort.png,
/// cohort-K-of-N.csv (as given: the caller folds case where it must).
bool IsCohortFileName(const std::string& name);

/// The columns a manifest may have, `case` and `segmentation` required.
const std::vector<std::string>& CohortManifestColumns();

/// Reads MANIFEST.csv: a header naming its columns (in any order: case, segmentation, poses,
/// tips, plan, scalpel), then a case per line (blank lines and lines starting with '#' skipped);
/// a cell may be double-quoted ("" for a quote) to hold a comma. Throws InputError(file, "line N:
/// ...") for an unknown or repeated column, a required one missing, a line with another number
/// of cells, an empty case or segmentation, a case name that cannot be a folder's or is given
/// twice, and no case at all. Files are not opened here: a case whose files are missing fails
/// alone, when it runs.
std::vector<CohortCase> ReadCohortManifest(const std::string& file);

/// Splits one CSV line into cells, double quotes honoured. Throws InputError(source, problem)
/// for a quote left open or text after a closing quote.
std::vector<std::string> SplitCsvLine(const std::string& line, const std::string& source);
} // namespace vp

#endif
