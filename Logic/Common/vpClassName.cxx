#include "vpClassName.h"

#include <cctype>

namespace vp
{
std::string ClassNameProblem(const std::string& name)
{
  constexpr std::size_t MaxLength = 64;
  if (name.empty())
  {
    return "a class needs a name";
  }
  if (name.size() > MaxLength)
  {
    return "a class name has at most " + std::to_string(MaxLength) + " characters";
  }
  if (!std::isalpha(static_cast<unsigned char>(name[0])))
  {
    return "a class name starts with a letter";
  }
  for (const char c : name)
  {
    const auto u = static_cast<unsigned char>(c);
    if (!(u < 128 && (std::isalnum(u) || c == '_' || c == '-')))
    {
      return "a class name holds letters, digits, '_' and '-' only";
    }
  }
  return std::string();
}
} // namespace vp
