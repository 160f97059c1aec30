#include "vpJsonFile.h"

#include "vpInputError.h"
#include "vpRegularFile.h"

#include <fstream>

namespace vp
{
std::ifstream OpenJsonFile(const std::string& fileName, const std::string& what)
{
  RegularFileSize(fileName, "cannot open as " + what, "cannot open as " + what);
  std::ifstream in(fileName);
  if (!in)
  {
    throw InputError(fileName, "cannot open as " + what);
  }
  return in;
}

std::string JsonErrorText(const nlohmann::json::exception& e)
{
  const std::string reason = e.what();
  const std::size_t bracket = reason.find(']');
  return reason.substr(bracket == std::string::npos ? 0 : bracket + 2);
}

nlohmann::json ReadJsonFile(const std::string& fileName, const std::string& what)
{
  std::ifstream in = OpenJsonFile(fileName, what);
  try
  {
    return nlohmann::json::parse(in);
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(fileName, "not valid JSON: " + JsonErrorText(e));
  }
}
} // namespace vp
