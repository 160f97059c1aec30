// The only translation unit that includes ITK's transform headers: they are heavy.
#include "vpItkTransformFile.h"

#include "vpInputError.h"
#include "vpText.h"

#ifdef __clang__
#include "vpItkClangCompat.h" // before any ITK header
#endif
#include <itkAffineTransform.h>
#include <itkHDF5TransformIO.h>
#include <itkMatlabTransformIO.h>
#include <itkTransform.h>
#include <itkTransformFactoryBase.h>
#include <itkTxtTransformIO.h>

#include <cmath>
#include <filesystem>

namespace vp
{
namespace
{
/// The extension, lower case, with its dot.
std::string ExtensionOf(const std::string& fileName)
{
  return LowerCase(std::filesystem::path(fileName).extension().string());
}

/// ITK's exception text is several lines with source locations; the user needs its last one.
std::string OneLine(const std::string& description)
{
  std::string text = description;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\r'))
  {
    text.pop_back();
  }
  const auto newline = text.find_last_of('\n');
  if (newline != std::string::npos)
  {
    text = text.substr(newline + 1);
  }
  // "ITK ERROR: TxtTransformIOTemplate(0x55d0c8a0): Tags must be delimited by :" says its
  // problem after the object's address.
  const auto address = text.find("(0x");
  const auto colon = address == std::string::npos ? address : text.find("): ", address);
  return colon == std::string::npos ? text : text.substr(colon + 3);
}
using TransformIO = itk::TransformIOBaseTemplate<double>;

/// The format is chosen by the extension rather than by ITK's IO factory: no factory registration
/// to depend on, and a file named .tfm holding HDF5 is refused rather than guessed. The transform
/// types are made by name through ITK's transform factory, whose built-in types are registered
/// here (once; ITK ignores a second registration).
TransformIO::Pointer TransformIOFor(const std::string& fileName)
{
  itk::TransformFactoryBase::RegisterDefaultTransforms();
  const std::string ext = ExtensionOf(fileName);
  if (ext == ".h5" || ext == ".hdf5")
  {
    return itk::HDF5TransformIOTemplate<double>::New().GetPointer();
  }
  if (ext == ".tfm" || ext == ".txt")
  {
    return itk::TxtTransformIOTemplate<double>::New().GetPointer();
  }
  if (ext == ".mat")
  {
    return itk::MatlabTransformIOTemplate<double>::New().GetPointer();
  }
  throw InputError(fileName, "not an ITK transform file (expected .h5, .tfm, .txt or .mat)");
}
} // namespace

bool IsItkTransformFileName(const std::string& fileName)
{
  const std::string ext = ExtensionOf(fileName);
  return ext == ".h5" || ext == ".hdf5" || ext == ".tfm" || ext == ".txt" || ext == ".mat";
}

Matrix4 ReadItkLinearTransform(const std::string& fileName)
{
  using Transform3 = itk::Transform<double, 3, 3>;
  const auto io = TransformIOFor(fileName);
  std::error_code error;
  if (!std::filesystem::is_regular_file(fileName, error))
  {
    throw InputError(fileName, "no such file");
  }
  if (!io->CanReadFile(fileName.c_str()))
  {
    throw InputError(fileName, "not a transform file ITK can read as " + ExtensionOf(fileName).substr(1));
  }
  io->SetFileName(fileName);
  try
  {
    io->Read();
  }
  catch (const itk::ExceptionObject& e)
  {
    throw InputError(fileName, "not a transform file ITK can read: " + OneLine(e.GetDescription()));
  }
  const TransformIO::TransformListType& transforms = io->GetTransformList();
  if (transforms.size() != 1)
  {
    throw InputError(fileName, "holds " + std::to_string(transforms.size()) +
        " transforms; a registration is one linear transform (a composition is stored as one CompositeTransform)");
  }
  const auto* transform = dynamic_cast<const Transform3*>(transforms.front().GetPointer());
  if (!transform)
  {
    throw InputError(fileName, "holds " + transforms.front()->GetTransformTypeAsString() +
        ", not a 3-D transform of points");
  }
  if (transform->GetTransformCategory() != Transform3::TransformCategoryEnum::Linear)
  {
    throw InputError(fileName, "holds " + transform->GetTransformTypeAsString() +
        ", not a linear transform: a registration here is rigid");
  }
  // Through the generic interface rather than a cast to a matrix type: every linear type,
  // composites included, is an origin and three axes.
  const auto origin = transform->TransformPoint(Transform3::InputPointType(0.0));
  Matrix4 m{};
  for (int row = 0; row < 3; ++row)
  {
    m[4 * row + 3] = origin[row];
  }
  for (int column = 0; column < 3; ++column)
  {
    Transform3::InputPointType unit(0.0);
    unit[column] = 1.0;
    const auto image = transform->TransformPoint(unit);
    for (int row = 0; row < 3; ++row)
    {
      m[4 * row + column] = image[row] - origin[row];
    }
  }
  m[15] = 1.0;
  for (double v : m)
  {
    if (!std::isfinite(v))
    {
      throw InputError(fileName, "the transform is not finite");
    }
  }
  return m;
}

void WriteItkLinearTransform(const std::string& fileName, const Matrix4& m)
{
  using Affine = itk::AffineTransform<double, 3>;
  auto affine = Affine::New();
  Affine::MatrixType matrix;
  Affine::OutputVectorType offset;
  for (int row = 0; row < 3; ++row)
  {
    for (int column = 0; column < 3; ++column)
    {
      matrix[row][column] = m[4 * row + column];
    }
    offset[row] = m[4 * row + 3];
  }
  affine->SetMatrix(matrix);
  affine->SetOffset(offset);
  const auto io = TransformIOFor(fileName);
  TransformIO::ConstTransformListType list{ affine.GetPointer() };
  io->SetTransformList(list);
  io->SetFileName(fileName);
  try
  {
    io->Write();
  }
  catch (const itk::ExceptionObject& e)
  {
    throw InputError(fileName, "cannot write the transform: " + OneLine(e.GetDescription()));
  }
}
} // namespace vp
