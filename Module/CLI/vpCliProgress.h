#ifndef vpCliProgress_h
#define vpCliProgress_h

// Progress as 3D Slicer reads it from a CLI's standard output: the last complete
// <filter-progress> (0 to 1) moves the module's progress bar and the last <filter-comment> is
// its message (vtkSlicerCLIModuleLogic); <filter-start> and <filter-end> frame the run and are
// stripped from the output Slicer shows. One tag per line, flushed, and only when the value or
// the text changed, so a fast loop does not flood the pipe. Nothing is written before the first
// stage a program reports, after its inputs are checked: a refused run prints only its one line.

#include <string>

namespace vp
{
namespace cli
{
class FilterProgress
{
public:
  explicit FilterProgress(std::string program);
  FilterProgress(const FilterProgress&) = delete;
  FilterProgress& operator=(const FilterProgress&) = delete;

  /// The stage now running and the share of the whole run done (clamped to 0..1; the bar only
  /// moves forwards). The first call writes <filter-start>; then a new comment is written when the
  /// stage changes, the fraction when it moved by at least a hundredth.
  void Stage(const std::string& comment, double fractionDone);
  /// <filter-progress>1 and <filter-end> with the run's time.
  void Finish();

private:
  std::string Program, Comment;
  double Done = 0.0;
  double StartMs = 0.0;
  bool Started = false;
};
} // namespace cli
} // namespace vp

#endif
