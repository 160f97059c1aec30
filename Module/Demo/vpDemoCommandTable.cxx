#include "vpDemoCommands.h"

namespace vp
{
const std::vector<CommandEntry>& DemoCommandTable()
{
  static const std::vector<CommandEntry> table{
    { "demo", DescribeDemoCommand, RunDemoCommand },
    { "selftest", DescribeSelfTestCommand, RunSelfTestCommand },
    { "bench", DescribeBenchCommand, RunBenchCommand },
    { "phantom", DescribePhantomCommand, RunPhantomCommand },
  };
  return table;
}
} // namespace vp
