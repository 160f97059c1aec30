#include "vpImageComparison.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace vp
{
namespace
{
vtkSmartPointer<vtkImageData> ReadPng(const std::string& file)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
  {
    return nullptr;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkSmartPointer<vtkImageData> image = reader->GetOutput();
  return image->GetNumberOfPoints() > 0 && image->GetNumberOfScalarComponents() >= 3 ? image : nullptr;
}
} // namespace

ImageDifference CompareImages(
  const std::string& actualFile, const std::string& baselineFile, const std::string& differenceFile, int threshold)
{
  ImageDifference result;
  auto actual = ReadPng(actualFile);
  auto baseline = ReadPng(baselineFile);
  if (!actual || !baseline)
  {
    return result;
  }
  int da[3], db[3];
  actual->GetDimensions(da);
  baseline->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    return result;
  }
  result.SameSize = true;
  const int ca = actual->GetNumberOfScalarComponents(), cb = baseline->GetNumberOfScalarComponents();
  const auto* pa = static_cast<const unsigned char*>(actual->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(baseline->GetScalarPointer());
  vtkNew<vtkImageData> difference;
  difference->SetDimensions(da[0], da[1], 1);
  difference->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* pd = static_cast<unsigned char*>(difference->GetScalarPointer());
  const long long pixels = static_cast<long long>(da[0]) * da[1];
  long long different = 0;
  double sum = 0;
  for (long long i = 0; i < pixels; ++i)
  {
    int worst = 0;
    for (int k = 0; k < 3; ++k)
    {
      const int d = std::abs(int(pa[i * ca + k]) - int(pb[i * cb + k]));
      worst = std::max(worst, d);
      sum += d;
    }
    const bool differs = worst > threshold;
    different += differs ? 1 : 0;
    for (int k = 0; k < 3; ++k)
    {
      pd[i * 3 + k] = differs ? 255 : static_cast<unsigned char>(pb[i * cb + k] / 4);
    }
  }
  result.FractionDifferent = static_cast<double>(different) / pixels;
  result.MeanAbsDifference = sum / (3.0 * pixels);
  if (!differenceFile.empty())
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(differenceFile.c_str());
    writer->SetInputData(difference);
    writer->Write();
  }
  return result;
}
} // namespace vp
