#include "vpJsonFile.h"

#include "vpInputError.h"
#include "vpRegularFile.h"

#include <fstream>

namespace vp
{
/// Reads the file in blocks, counting the characters of the value being read: inside a string
/// (escapes followed), or a run of characters that are not JSON's punctuation or blanks.
class JsonFileInput::Guard : public std::streambuf
{
public:
  Guard(const std::string& fileName, const std::string& what)
    : Name(fileName)
  {
    RegularFileSize(fileName, "is a folder, cannot open as " + what,
      "is not a regular file (a device, pipe or socket), cannot open as " + what);
    this->File.open(fileName, std::ios::binary);
    if (!this->File)
    {
      throw InputError(fileName, "cannot open as " + what);
    }
  }

protected:
  int_type underflow() override
  {
    if (this->gptr() < this->egptr())
    {
      return traits_type::to_int_type(*this->gptr());
    }
    const std::streamsize n = this->File.rdbuf()->sgetn(this->Block, sizeof(this->Block));
    if (n <= 0)
    {
      return traits_type::eof();
    }
    this->Scan(this->Block, static_cast<std::size_t>(n));
    this->setg(this->Block, this->Block, this->Block + n);
    return traits_type::to_int_type(*this->gptr());
  }

private:
  void Scan(const char* p, std::size_t n)
  {
    for (std::size_t i = 0; i < n; ++i, ++this->Offset)
    {
      const char c = p[i];
      if (this->InString)
      {
        if (this->Escaped)
        {
          this->Escaped = false;
        }
        else if (c == '\\')
        {
          this->Escaped = true;
        }
        else if (c == '"')
        {
          this->InString = false;
          this->Length = 0;
          continue;
        }
      }
      else if (c == '"')
      {
        this->InString = true;
        this->Length = 0;
        continue;
      }
      else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',' || c == ':' || c == '[' || c == ']' ||
        c == '{' || c == '}')
      {
        this->Length = 0;
        continue;
      }
      if (++this->Length > MaxValueCharacters)
      {
        throw InputError(this->Name, "a value of more than " + std::to_string(MaxValueCharacters) + " characters at byte " +
            std::to_string(this->Offset - MaxValueCharacters) + ": not something this file holds");
      }
    }
  }

  std::string Name;
  std::ifstream File;
  char Block[65536];
  std::size_t Offset = 0, Length = 0;
  bool InString = false, Escaped = false;
};

JsonFileInput::JsonFileInput(const std::string& fileName, const std::string& what)
  : std::istream(nullptr)
  , Buffer(std::make_unique<Guard>(fileName, what))
{
  this->rdbuf(this->Buffer.get());
}

JsonFileInput::~JsonFileInput() = default;

std::string JsonErrorText(const nlohmann::json::exception& e)
{
  const std::string reason = e.what();
  const std::size_t bracket = reason.find(']');
  return reason.substr(bracket == std::string::npos ? 0 : bracket + 2);
}

nlohmann::json ReadJsonFile(const std::string& fileName, const std::string& what)
{
  JsonFileInput in(fileName, what);
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
