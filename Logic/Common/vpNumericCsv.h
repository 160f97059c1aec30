#ifndef vpNumericCsv_h
#define vpNumericCsv_h

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

namespace vp
{
/// One line of numbers from a CSV file, with its line number (from 1) for messages.
struct NumericRow
{
  std::size_t Line = 0;
  std::vector<double> Values;
};

/// Splits "a,b,c" (blanks around commas allowed) into finite numbers. Returns false with a short
/// problem ("NaN or infinite value", "'...' is not a list of numbers") otherwise.
bool ParseNumbers(const std::string& text, std::vector<double>& values, std::string& problem);
/// The same for numbers separated by any run of blanks, line breaks and commas ("1 0 0 10  0 1 0
/// 20", as PLUS writes a transform, or a matrix over four lines).
bool ParseSeparatedNumbers(const std::string& text, std::vector<double>& values, std::string& problem);

/// Reads the numeric lines of a CSV file: a first line whose first field is not a number is a
/// header, blank lines and lines starting with '#' are skipped. Throws vp::InputError naming the
/// file and the line for anything else, naming what the file should hold (e.g. "a point list")
/// when it cannot be opened or holds no row.
std::vector<NumericRow> ReadNumericCsv(const std::string& fileName, const std::string& what);

/// The same rows one at a time, for files too long to hold (a pose stream of an hour): the
/// same checks and messages, with "nothing in it" thrown by the first Next() that finds no row.
class NumericCsvReader
{
public:
  NumericCsvReader(const std::string& fileName, const std::string& what);
  /// The next row; false at the end of the file.
  bool Next(NumericRow& row);
  const std::string& FileName() const { return this->Name; }
  /// The header's fields, blanks around them trimmed: the last line before the first row whose
  /// first field is no number; empty when there is none. Known once the first row is read.
  const std::vector<std::string>& Header() const { return this->HeaderFields; }
  /// The comment lines before the first row, without their '#' and the blanks around them: where
  /// a file may say how its numbers are to be read.
  const std::vector<std::string>& LeadingComments() const { return this->Comments; }
  /// The longest line read (characters, without its end); a longer one is refused.
  static constexpr std::size_t MaxLineCharacters = 65536;

private:
  /// The next line into Line, without its end and without a UTF-8 byte order mark on the first;
  /// false at the end of the file.
  bool ReadLine();
  std::string Name;
  std::string What;
  std::ifstream In;
  std::string Line;
  std::size_t LineNumber = 0;
  std::size_t Rows = 0;
  std::vector<std::string> HeaderFields;
  std::vector<std::string> Comments;
};

/// text without the blanks (spaces, tabs, carriage returns) at its ends.
std::string TrimBlanks(const std::string& text);
} // namespace vp

#endif
