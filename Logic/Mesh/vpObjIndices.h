#ifndef vpObjIndices_h
#define vpObjIndices_h

#include <string>

namespace vp
{
/// Refuses an OBJ file whose faces, lines or points name a vertex, texture coordinate or normal
/// that is not defined before them, before VTK's reader indexes with it unchecked (a face
/// `f 1/1 2/1 3/1` in a file without `vt` lines crashed it). Indices are whole numbers, positive
/// (from the first of their kind) or negative (back from the last one so far), never 0; an entry
/// is v, v/vt, v//vn or v/vt/vn, every entry of a line in the same form (a trailing slash beside
/// other forms crashed VTK's reader too). Throws vp::InputError(fileName, "line N: ...").
void CheckObjIndices(const std::string& bytes, const std::string& fileName);
} // namespace vp

#endif
