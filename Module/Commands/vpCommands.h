#ifndef vpCommands_h
#define vpCommands_h

#include <string>
#include <vector>

namespace vp
{
/// Each subcommand takes the arguments after its name, writes its result to stdout (or files),
/// and returns the process exit code. Bad input throws InputError, caught by main.
int RunDistanceCommand(const std::vector<std::string>& args);
int RunBenchCommand(const std::vector<std::string>& args);
int RunPhantomCommand(const std::vector<std::string>& args);
int RunModelsCommand(const std::vector<std::string>& args);
int RunTrackCommand(const std::vector<std::string>& args);
int RunRegisterCommand(const std::vector<std::string>& args);
int RunDemoCommand(const std::vector<std::string>& args);
int RunViewCommand(const std::vector<std::string>& args);
int RunSelfTestCommand(const std::vector<std::string>& args);
} // namespace vp

#endif
