#ifndef vpPngFile_h
#define vpPngFile_h

#include <string>

class vtkImageData;

namespace vp
{
/// Encodes an image (unsigned char RGB or RGBA) as PNG in memory and writes it as every output
/// is written (WriteFileAtomically): whole or not at all, through a link, never replacing a
/// device or a pipe with a regular file. Throws InputError naming the file when it cannot.
void WritePngAtomically(vtkImageData* image, const std::string& fileName);
} // namespace vp

#endif
