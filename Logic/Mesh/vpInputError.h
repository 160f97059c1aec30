#ifndef vpInputError_h
#define vpInputError_h

#include <sstream>
#include <stdexcept>
#include <string>

namespace vp
{
/// An input the user gave us is not what it claims to be. The message is one line that names the
/// file (or the argument) and the problem, ready to be printed as it is.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& message)
    : std::runtime_error(message)
  {
  }
  InputError(const std::string& source, const std::string& problem)
    : std::runtime_error(source + ": " + problem)
  {
  }
};

/// A number as a message shows it: the shortest form to the given significant digits ("0.9",
/// "1.41421"), not std::to_string's fixed six decimals.
inline std::string NumberText(double value, int significantDigits = 6)
{
  std::ostringstream out;
  out.precision(significantDigits);
  out << value;
  return out.str();
}
} // namespace vp

#endif
