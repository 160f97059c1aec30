#ifndef vpDecimal_h
#define vpDecimal_h

#include <cmath>
#include <cstdlib>
#include <string>

namespace vp
{
/// The end of a plain decimal number at p ([+-]digits[.digits][e[+-]digits], or [+-].digits...),
/// or p itself when none starts there. What strtod also reads but a person never means as a
/// coordinate or a setting (hexadecimal "0x10", "inf", "nan") is no number here.
inline const char* ScanDecimal(const char* p)
{
  const char* q = p;
  if (*q == '+' || *q == '-')
  {
    ++q;
  }
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  const char* mantissa = q;
  while (digit(*q))
  {
    ++q;
  }
  bool any = q > mantissa;
  if (*q == '.')
  {
    const char* fraction = ++q;
    while (digit(*q))
    {
      ++q;
    }
    any = any || q > fraction;
  }
  if (!any)
  {
    return p;
  }
  if (*q == 'e' || *q == 'E')
  {
    const char* e = q + 1;
    if (*e == '+' || *e == '-')
    {
      ++e;
    }
    if (digit(*e))
    {
      while (digit(*e))
      {
        ++e;
      }
      q = e;
    }
  }
  // "0x10": the 0 is a number, and what follows it is not.
  return q;
}

/// Whether text is one plain decimal number and nothing else (ScanDecimal), finite; its value.
inline bool ParseDecimal(const std::string& text, double& value)
{
  const char* begin = text.c_str();
  if (text.empty() || ScanDecimal(begin) != begin + text.size())
  {
    return false;
  }
  value = std::strtod(begin, nullptr);
  return std::isfinite(value);
}
} // namespace vp

#endif
