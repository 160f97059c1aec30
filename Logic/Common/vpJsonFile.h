#ifndef vpJsonFile_h
#define vpJsonFile_h

#include <nlohmann/json.hpp>

#include <string>

namespace vp
{
/// Parses a JSON file. Throws vp::InputError naming the file: "no such file", "cannot open as
/// <what>", or "not valid JSON: <where the parser stopped and why>". The caller checks the shape.
nlohmann::json ReadJsonFile(const std::string& fileName, const std::string& what);
} // namespace vp

#endif
