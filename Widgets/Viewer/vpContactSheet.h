#ifndef vpContactSheet_h
#define vpContactSheet_h

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkImageData;

namespace vp
{
/// One picture of a contact sheet and the line under it.
struct ContactSheetEntry
{
  vtkSmartPointer<vtkImageData> Image; ///< unsigned char RGB
  std::string Caption;
};

/// A run's key frames on one page: each picture scaled to thumbWidthPx (aspect kept), in rows of
/// columns, each captioned underneath in up to three lines (wrapped at the thumbnail's width), on a
/// dark background. Returns the sheet (RGB).
vtkSmartPointer<vtkImageData> MakeContactSheet(
  const std::vector<ContactSheetEntry>& entries, int columns = 3, int thumbWidthPx = 420);
} // namespace vp

#endif
