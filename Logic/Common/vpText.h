#ifndef vpText_h
#define vpText_h

#include <algorithm>
#include <cctype>
#include <string>

namespace vp
{
/// Whether text ends with suffix, exactly (case counts).
inline bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// text in lower case (ASCII letters; other bytes as they are).
inline std::string LowerCase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}
} // namespace vp

#endif
