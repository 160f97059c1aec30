#ifndef vpCliValues_h
#define vpCliValues_h

// How the text of a command line is read as the parameter kinds of vpCliDescription.h: shared by
// the table's own check, the parser, the help and the return values. Not part of the contract.

#include "vpCliDescription.h"

#include <string>
#include <vector>

namespace vp
{
namespace cli
{
/// A C identifier: a letter or '_', then letters, digits or '_'.
bool IsIdentifier(const std::string& text);
/// The simple types: numbers, booleans, strings, enumerations, vectors (not files, points, data).
bool IsSimpleType(ParameterType type);
bool IsNumeric(ParameterType type);
/// Whether the type names a file or folder, which SEM ties to a channel.
bool IsData(ParameterType type);
/// A finite number and nothing else (no leading blank); false otherwise.
bool ParseDouble(const std::string& text, double& value);
/// Numbers separated by commas and/or blanks ("1,2,3", "1 2 3"), as Slicer and people write them.
bool ParseNumberList(const std::string& text, std::vector<double>& numbers);
std::string JoinElements(const std::vector<std::string>& elements, const char* separator);
/// Checks one value against its parameter; throws vp::InputError naming the parameter.
void CheckValue(const Parameter& p, const std::string& value);
} // namespace cli
} // namespace vp

#endif
