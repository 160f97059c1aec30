#ifndef vpClassName_h
#define vpClassName_h

#include <string>
#include <vector>

namespace vp
{
/// Whether name can name a vessel class. A class's name becomes a file name (<class>.stl), the
/// prefix of CSV columns (<class>_mm) and a JSON key, so it is 1 to 64 letters, digits, '_' and
/// '-', starting with a letter: no blank, comma, quote, slash or line break. Returns the problem
/// in a few words ("" when the name is fine).
std::string ClassNameProblem(const std::string& name);

/// The known class one or two letters from name (an edit, a missing or extra letter, two letters
/// swapped: "portal_vien"), or "" when name is known or far from every known class: a near miss
/// is a typing error, never a new class.
std::string NearMissOf(const std::string& name, const std::vector<std::string>& known);

/// A tumour's id as a person reads it: "tumour_03" and "Tumour-3" as "tumour 03", "tumour 3";
/// any other id after the word: "lesion" as "tumour lesion" (never "tumour tumour_03").
std::string TumourSpoken(const std::string& id);
} // namespace vp

#endif
