// Each subcommand's parser and --help come from one description (issue 15): what the help lists
// is exactly what the parser takes, and what it does not list is refused as bad usage.
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>

namespace
{
/// The commands the program's --help lists ("  name       title").
std::vector<std::string> ListedCommands(const std::string& dir)
{
  const vp::test::ToolRun help = vp::test::RunTool(dir, "--help");
  std::vector<std::string> names;
  std::istringstream lines(help.Out.substr(help.Out.find("commands:")));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line) && line.rfind("  ", 0) == 0)
  {
    std::istringstream words(line);
    std::string name;
    words >> name;
    names.push_back(name);
  }
  return names;
}

/// An option its --help lists: the flag and whether it takes a value.
struct ListedOption
{
  std::string Flag;
  bool TakesValue;
};

std::vector<ListedOption> ListedOptions(const std::string& help)
{
  // "  --frame-budget-ms MS", "  -o, --output OUTDIR", "  --repair"
  static const std::regex head(R"(^  (?:-[a-z], )?(--[a-z][a-z0-9-]*)( \S+)?$)");
  std::vector<ListedOption> options;
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);)
  {
    std::smatch m;
    if (std::regex_match(line, m, head))
    {
      options.push_back({ m[1], m[2].matched });
    }
  }
  return options;
}
} // namespace

TEST(CommandHelp, ListsExactlyWhatTheParserTakes)
{
  const std::string dir = vp::test::MakeTempDir("command_help");
  const std::vector<std::string> commands = ListedCommands(dir);
  ASSERT_EQ(commands.size(), 13u);
  for (const std::string& command : commands)
  {
    const vp::test::ToolRun help = vp::test::RunTool(dir, command + " --help");
    ASSERT_EQ(help.ExitCode, 0) << command;
    EXPECT_EQ(help.Out.rfind("usage: vesselproximity " + command, 0), 0u) << help.Out;
    const std::vector<ListedOption> options = ListedOptions(help.Out);
    EXPECT_GE(options.size(), 1u) << command;
    for (const ListedOption& o : options)
    {
      // A flag the parser knows reads its value and goes on to the unknown one after it (or
      // refuses the value "1"); a flag it did not know would be refused itself.
      const std::string line = command + " " + o.Flag + (o.TakesValue ? " 1" : "") + " --zz-unlisted";
      const vp::test::ToolRun r = vp::test::RunTool(dir, line);
      EXPECT_NE(r.ExitCode, 0) << line;
      EXPECT_EQ(r.Err.find(o.Flag + ": unknown option"), std::string::npos) << line << "\n" << r.Err;
      EXPECT_EQ(r.Out, "") << line;
    }
    const vp::test::ToolRun unknown = vp::test::RunTool(dir, command + " --zz-unlisted");
    EXPECT_EQ(unknown.ExitCode, 2) << command;
    EXPECT_EQ(unknown.Err, "vesselproximity: error: --zz-unlisted: unknown option (see vesselproximity " + command + " --help)\n");
    EXPECT_EQ(unknown.Out, "");
  }
  std::filesystem::remove_all(dir);
}
