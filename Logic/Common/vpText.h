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

/// Words joined in camel case, '_', '-' and ' ' between them: "frame-budget-ms" as
/// "frameBudgetMs" (a CLI parameter's name), "portal_vein" as "PortalVein" with upperFirst (an
/// OpenIGTLink device's).
inline std::string CamelCase(const std::string& words, bool upperFirst)
{
  std::string camel;
  bool upper = upperFirst;
  for (char c : words)
  {
    if (c == '_' || c == '-' || c == ' ')
    {
      upper = true;
      continue;
    }
    camel += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return camel;
}
} // namespace vp

#endif
