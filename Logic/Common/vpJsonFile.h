#ifndef vpJsonFile_h
#define vpJsonFile_h

#include <nlohmann/json.hpp>

#include <istream>
#include <memory>
#include <string>

namespace vp
{
/// Parses a JSON file. Throws vp::InputError naming the file: "no such file", "cannot open as
/// <what>", "not valid JSON: <where the parser stopped and why>", or a value too long (below).
/// The caller checks the shape.
nlohmann::json ReadJsonFile(const std::string& fileName, const std::string& what);

/// A JSON file opened for a parser, after the checks ReadJsonFile makes (a regular file: a FIFO
/// with no writer would block the open, /dev/zero never ends), read through a guard that refuses
/// one value (a string, a number, a literal) longer than MaxValueCharacters as it comes, with
/// vp::InputError naming the file and the byte: nlohmann holds a value whole, and a 200 MB string
/// or a 2 GB number took the machine's memory before the parser could say anything.
class JsonFileInput : public std::istream
{
public:
  static constexpr std::size_t MaxValueCharacters = 1u << 20;
  JsonFileInput(const std::string& fileName, const std::string& what);
  ~JsonFileInput() override;
  JsonFileInput(const JsonFileInput&) = delete;
  JsonFileInput& operator=(const JsonFileInput&) = delete;

private:
  class Guard;
  std::unique_ptr<Guard> Buffer;
};

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string JsonErrorText(const nlohmann::json::exception& e);
} // namespace vp

#endif
