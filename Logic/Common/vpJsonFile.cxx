#include "vpJsonFile.h"

#include "vpInputError.h"

#include <filesystem>
#include <fstream>

namespace vp
{
nlohmann::json ReadJsonFile(const std::string& fileName, const std::string& what)
{
  std::error_code ec;
  // Checked before opening: a FIFO with no writer would block the open, /dev/zero never ends.
  if (!std::filesystem::is_regular_file(fileName, ec))
  {
    throw InputError(fileName, std::filesystem::exists(fileName, ec) ? "cannot open as " + what : "no such file");
  }
  std::ifstream in(fileName);
  if (!in)
  {
    throw InputError(fileName, "cannot open as " + what);
  }
  try
  {
    return nlohmann::json::parse(in);
  }
  catch (const nlohmann::json::exception& e)
  {
    // nlohmann's message starts "[json.exception.parse_error.101] "; keep what follows.
    std::string reason = e.what();
    reason = reason.substr(reason.find(']') == std::string::npos ? 0 : reason.find(']') + 2);
    throw InputError(fileName, "not valid JSON: " + reason);
  }
}
} // namespace vp
