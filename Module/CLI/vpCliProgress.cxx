#include "vpCliProgress.h"

#include "vpClock.h"

#include <algorithm>
#include <cstdio>

namespace vp
{
namespace cli
{
namespace
{
/// Text inside a tag: Slicer finds tags by their '<', so none may be in it.
std::string TagText(std::string text)
{
  std::replace(text.begin(), text.end(), '<', '(');
  std::replace(text.begin(), text.end(), '>', ')');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}
} // namespace

FilterProgress::FilterProgress(std::string program)
  : Program(std::move(program))
  , StartMs(NowMs())
{
}

void FilterProgress::Stage(const std::string& comment, double fractionDone)
{
  const std::string text = TagText(comment);
  if (!this->Started)
  {
    this->Started = true;
    this->Comment = text;
    std::printf("<filter-start><filter-name>%s</filter-name><filter-comment>%s</filter-comment></filter-start>\n",
      TagText(this->Program).c_str(), text.c_str());
  }
  const double done = std::clamp(fractionDone, this->Done, 1.0);
  bool wrote = false;
  if (text != this->Comment)
  {
    this->Comment = text;
    std::printf("<filter-comment>%s</filter-comment>\n", text.c_str());
    wrote = true;
  }
  if (done >= this->Done + 0.01 || (wrote && done > this->Done))
  {
    this->Done = done;
    std::printf("<filter-progress>%.3f</filter-progress>\n", done);
    wrote = true;
  }
  if (wrote)
  {
    std::fflush(stdout);
  }
}

void FilterProgress::Finish()
{
  if (!this->Started)
  {
    this->Stage("Done", 1.0);
  }
  std::printf("<filter-progress>1</filter-progress>\n<filter-end><filter-name>%s</filter-name><filter-time>%.3f</filter-time></filter-end>\n",
    TagText(this->Program).c_str(), (NowMs() - this->StartMs) / 1000.0);
  std::fflush(stdout);
}
} // namespace cli
} // namespace vp
