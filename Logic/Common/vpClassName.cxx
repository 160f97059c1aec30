#include "vpClassName.h"

#include <algorithm>
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

namespace
{
/// Edits (insert, delete, replace, swap two neighbours) from a to b: the optimal string
/// alignment distance.
std::size_t EditDistance(const std::string& a, const std::string& b)
{
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i)
  {
    d[i][0] = i;
  }
  for (std::size_t j = 0; j <= b.size(); ++j)
  {
    d[0][j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      d[i][j] = std::min({ d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1) });
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
      {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}
} // namespace

std::string NearMissOf(const std::string& name, const std::vector<std::string>& known)
{
  if (std::find(known.begin(), known.end(), name) != known.end())
  {
    return std::string();
  }
  std::string nearest;
  std::size_t best = 3;
  for (const std::string& k : known)
  {
    const std::size_t d = EditDistance(name, k);
    if (d < best)
    {
      best = d;
      nearest = k;
    }
  }
  return nearest;
}

std::string TumourSpoken(const std::string& id)
{
  std::string lower = id;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower.rfind("tumour", 0) != 0 && lower.rfind("tumor", 0) != 0)
  {
    return "tumour " + id;
  }
  std::string spoken = id;
  std::replace_if(spoken.begin(), spoken.end(), [](char c) { return c == '_' || c == '-'; }, ' ');
  return spoken;
}
} // namespace vp
