#include "vpPngFile.h"

#include "vpInputError.h"
#include "vpOutputFile.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkUnsignedCharArray.h>

namespace vp
{
void WritePngAtomically(vtkImageData* image, const std::string& fileName)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->WriteToMemoryOn();
  writer->Write();
  vtkUnsignedCharArray* bytes = writer->GetResult();
  if (writer->GetErrorCode() != 0 || !bytes || bytes->GetNumberOfValues() == 0)
  {
    throw InputError(fileName, "cannot write: PNG encoding failed");
  }
  WriteFileAtomically(fileName,
    std::string(reinterpret_cast<const char*>(bytes->GetPointer(0)), static_cast<std::size_t>(bytes->GetNumberOfValues())));
}
} // namespace vp
