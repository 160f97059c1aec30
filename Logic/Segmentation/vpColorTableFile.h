#ifndef vpColorTableFile_h
#define vpColorTableFile_h

#include <map>
#include <string>

namespace vp
{
/// The names a 3D Slicer colour table gives label values: what a labelmap volume's colour node
/// says its values are, which Slicer writes as a .ctbl file when it hands the volume to a CLI
/// (the volume's own file carries no names). Format (vtkMRMLColorTableStorageNode): '#' comment
/// lines ("# Color table file ...", "# N values"), then per defined colour "value name r g b a",
/// spaces in the name written as '_' (a lone '_' for no name), colours 0..255. Slicer's own colour
/// files (.txt) have the same lines.
///
/// Returns value -> name (underscores back to spaces; value 0 and unnamed entries left out).
/// Throws InputError naming the file and the line for anything else: a procedural colour file, a
/// value that is not an integer in 0..1,000,000 (Slicer's limit), a colour outside 0..255, a value
/// named twice, a line of too few fields, control characters, or a file of over 16 MB.
std::map<int, std::string> ReadColorTableNames(const std::string& fileName);
/// The same from text (fuzzing, tests); source names it in errors.
std::map<int, std::string> ParseColorTableNames(const std::string& text, const std::string& source);
} // namespace vp

#endif
