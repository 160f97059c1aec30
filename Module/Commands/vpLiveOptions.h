#ifndef vpLiveOptions_h
#define vpLiveOptions_h

// The options of a live OpenIGTLink stream, as live and view take them, declared once.

#include "vpCliDescription.h"
#include "vpIgtlLink.h"

#include <string>
#include <utility>
#include <vector>

namespace vp
{
/// --igtl HOST:PORT, --igtl-listen [HOST:]PORT, --pose-from HOST, --tool-name NAME, --pose-space, --pose-units,
/// --registration, --stale-ms MS, --duration-s S. toolRequired: whether --tool-name must be given
/// (view takes a stream only when one of --igtl and --igtl-listen is); withReading: whether the
/// reading options come too (view declares them already, for its recorded poses).
std::vector<cli::Parameter> LiveStreamOptions(bool toolRequired, bool withReading);
/// Whether the command line asks for a stream (--igtl or --igtl-listen).
bool WantsLiveStream(const cli::ParsedArguments& args);
/// The link those options describe; throws InputError naming the option.
IgtlLinkSettings ParseLiveStream(const cli::ParsedArguments& args);
/// --igtl-listen PORT (served on loopback) or HOST:PORT, a port 0 to 65535; throws InputError
/// naming the option.
std::pair<std::string, int> ParseListenAddress(const cli::ParsedArguments& args);
/// The link's events since the last call, a line each on stderr after "command: ".
void PrintLinkEvents(const std::string& command, IgtlLink& link);
/// --stale-ms (above 0) and --duration-s (0 or more); throw InputError naming the option.
double ParseStaleMs(const cli::ParsedArguments& args);
double ParseDurationS(const cli::ParsedArguments& args);
} // namespace vp

#endif
