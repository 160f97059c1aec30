#ifndef vpJsonFile_h
#define vpJsonFile_h

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace vp
{
/// Parses a JSON file. Throws vp::InputError naming the file: "no such file", "cannot open as
/// <what>", or "not valid JSON: <where the parser stopped and why>". The caller checks the shape.
nlohmann::json ReadJsonFile(const std::string& fileName, const std::string& what);

/// The file opened for a JSON parser, after the checks ReadJsonFile makes (a regular file: a FIFO
/// with no writer would block the open, /dev/zero never ends). Throws vp::InputError as it does.
std::ifstream OpenJsonFile(const std::string& fileName, const std::string& what);

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string JsonErrorText(const nlohmann::json::exception& e);
} // namespace vp

#endif
