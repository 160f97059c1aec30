// The only translation unit that includes ITK's transform headers: they are heavy.
#include "vpItkTransformFile.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpText.h"

#ifdef __clang__
#include "vpItkClangCompat.h" // before any ITK header
#endif
#include <itkAffineTransform.h>
#include <itkCompositeTransform.h>
#include <itkHDF5TransformIO.h>
#include <itkTransform.h>
#include <itkTransformFactoryBase.h>
#include <itkTxtTransformIO.h>

#include <H5Cpp.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

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
  throw InputError(fileName, "not an ITK transform file (expected .h5, .tfm or .txt)");
}

using Transform3 = itk::Transform<double, 3, 3>;

/// Refuses a transform type this reader cannot take as part of a rigid registration, and
/// parameter counts the type cannot hold, before ITK sets them: some of its types take their
/// parameters without counting them (a TranslationTransform with none read past its array).
void CheckTransformShape(const std::string& type, std::size_t parameters, std::size_t fixed, const std::string& fileName,
  const std::string& where)
{
  std::string name = type; // ITK reads a single-precision transform as its double twin
  const auto single = name.find("_float_");
  if (single != std::string::npos)
  {
    name.replace(single, 7, "_double_");
  }
  if (name == "CompositeTransform_double_3_3")
  {
    if (parameters != 0 || fixed != 0)
    {
      throw InputError(fileName, where + "a CompositeTransform has no parameters of its own");
    }
    return;
  }
  const itk::LightObject::Pointer object = itk::ObjectFactoryBase::CreateInstance(name.c_str());
  if (!object)
  {
    throw InputError(fileName, where + "'" + type + "' is not a transform type ITK knows");
  }
  object->UnRegister(); // the factory hands the object over with a reference of its own, as ITK's readers release it
  const auto* transform = dynamic_cast<const Transform3*>(object.GetPointer());
  if (!transform)
  {
    throw InputError(fileName, "holds " + type + ", not a 3-D transform of points");
  }
  if (transform->GetTransformCategory() != Transform3::TransformCategoryEnum::Linear)
  {
    throw InputError(fileName, "holds " + type + ", not a linear transform: a registration here is rigid");
  }
  if (transform->GetNumberOfParameters() != parameters || transform->GetFixedParameters().size() != fixed)
  {
    throw InputError(fileName, where + type + " takes " + std::to_string(transform->GetNumberOfParameters()) + " parameters and " +
        std::to_string(transform->GetFixedParameters().size()) + " fixed ones, the file gives " + std::to_string(parameters) +
        " and " + std::to_string(fixed));
  }
}

/// The numbers of a text transform file's Parameters or FixedParameters line: finite, blank
/// separated, nothing else.
std::size_t CountNumbers(const std::string& values, const std::string& fileName, const std::string& where)
{
  std::istringstream in(values);
  std::size_t count = 0;
  for (std::string word; in >> word;)
  {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size() || word.empty() || errno == ERANGE || !std::isfinite(v))
    {
      throw InputError(fileName, where + "'" + word.substr(0, 32) + "' is not a finite number");
    }
    ++count;
  }
  return count;
}

/// ITK's text format as ITK and Slicer write it, checked before ITK parses it: comments and
/// blank lines, and per transform a "Transform:" line followed by its "Parameters:" and
/// "FixedParameters:" (a CompositeTransform has neither), nothing else; the counts the type holds.
/// ITK's own parser takes a transform without parameters as the identity, and a malformed
/// parameter line as none (then crashes on some types).
void CheckTextTransformFile(const std::string& fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  std::string line, type, where;
  std::size_t number = 0;
  std::optional<std::size_t> parameters, fixed;
  auto finish = [&] {
    if (type.empty())
    {
      return;
    }
    const bool composite = type.rfind("CompositeTransform", 0) == 0;
    if (!composite && (!parameters || !fixed))
    {
      throw InputError(fileName, where + type + " has no " + (parameters ? "FixedParameters" : "Parameters") + " line");
    }
    CheckTransformShape(type, parameters.value_or(0), fixed.value_or(0), fileName, where);
  };
  while (std::getline(in, line))
  {
    ++number;
    // ITK and this check must see the same text: a control character (a NUL ends ITK's number
    // early) is no part of it.
    if (std::any_of(line.begin(), line.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r'; }))
    {
      throw InputError(fileName, "line " + std::to_string(number) + ": a control character: not a text transform file");
    }
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
    {
      line.pop_back();
    }
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    const auto colon = line.find(':');
    const std::string key = colon == std::string::npos ? line.substr(first) : line.substr(first, colon - first);
    const std::string value = colon == std::string::npos ? std::string() : line.substr(colon + 1);
    const std::string at = "line " + std::to_string(number) + ": ";
    if (key == "Transform")
    {
      finish();
      std::istringstream words(value);
      words >> type;
      if (type.empty() || type.size() > 64 || type.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos)
      {
        throw InputError(fileName, at + "not a transform type name");
      }
      where = at;
      parameters.reset();
      fixed.reset();
    }
    else if ((key == "Parameters" || key == "FixedParameters") && !type.empty())
    {
      auto& count = key == "Parameters" ? parameters : fixed;
      if (count)
      {
        throw InputError(fileName, at + "a second " + key + " line for one transform");
      }
      count = CountNumbers(value, fileName, at);
    }
    else
    {
      throw InputError(fileName, at + "expected a comment, Transform:, Parameters: or FixedParameters:");
    }
  }
  if (type.empty())
  {
    throw InputError(fileName, "no Transform: line: not an ITK transform file");
  }
  finish();
}

/// The same for ITK's HDF5 layout (/TransformGroup/N/TransformType, TransformParameters,
/// TransformFixedParameters), read through the HDF5 library ITK itself uses.
void CheckHdf5TransformFile(const std::string& fileName)
{
  H5::Exception::dontPrint();
  try
  {
    H5::H5File file(fileName, H5F_ACC_RDONLY);
    const H5::Group group = file.openGroup("/TransformGroup");
    const hsize_t count = group.getNumObjs();
    if (count == 0 || count > 64)
    {
      throw InputError(fileName, "holds " + std::to_string(count) + " transforms");
    }
    auto length = [&](const std::string& path) -> std::size_t {
      const H5::DataSpace space = file.openDataSet(path).getSpace();
      if (space.getSimpleExtentNdims() != 1)
      {
        throw InputError(fileName, path + " is not a list of numbers");
      }
      hsize_t dims[1] = { 0 };
      space.getSimpleExtentDims(dims);
      return static_cast<std::size_t>(dims[0]);
    };
    for (hsize_t i = 0; i < count; ++i)
    {
      const std::string path = "/TransformGroup/" + std::to_string(i);
      const H5::DataSet typeSet = file.openDataSet(path + "/TransformType");
      std::string type;
      typeSet.read(type, typeSet.getStrType());
      type = type.substr(0, type.find('\0'));
      if (type.empty() || type.size() > 64 || type.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos)
      {
        throw InputError(fileName, path + ": not a transform type name");
      }
      if (type.rfind("CompositeTransform", 0) == 0)
      {
        CheckTransformShape(type, 0, 0, fileName, path + ": ");
        continue;
      }
      CheckTransformShape(type, length(path + "/TransformParameters"), length(path + "/TransformFixedParameters"), fileName, path + ": ");
    }
  }
  catch (const H5::Exception& e)
  {
    throw InputError(fileName, "not an ITK transform file in HDF5: " + e.getDetailMsg());
  }
}
} // namespace

bool IsItkTransformFileName(const std::string& fileName)
{
  const std::string ext = ExtensionOf(fileName);
  return ext == ".h5" || ext == ".hdf5" || ext == ".tfm" || ext == ".txt";
}

Matrix4 ReadItkLinearTransform(const std::string& fileName)
{
  const std::string ext = ExtensionOf(fileName);
  const auto io = TransformIOFor(fileName);
  std::error_code error;
  if (!std::filesystem::is_regular_file(fileName, error))
  {
    throw InputError(fileName, "no such file");
  }
  if (std::filesystem::file_size(fileName, error) > (1u << 20))
  {
    throw InputError(fileName, "over 1 MiB: not a linear transform file");
  }
  if (!io->CanReadFile(fileName.c_str()))
  {
    throw InputError(fileName, "not a transform file ITK can read as " + ext.substr(1));
  }
  if (ext == ".h5" || ext == ".hdf5")
  {
    CheckHdf5TransformFile(fileName);
  }
  else
  {
    CheckTextTransformFile(fileName);
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
  catch (const std::exception&)
  {
    // ITK's parser lets the standard library's errors through (a truncated type name throws
    // std::out_of_range from a string replace): their text says nothing about the file.
    throw InputError(fileName, "not a transform file ITK can read: a malformed transform line");
  }
  const TransformIO::TransformListType& transforms = io->GetTransformList();
  // A composite is written as its own line and then its parts, as ITK's file reader rebuilds it.
  const bool composite =
    !transforms.empty() && transforms.front()->GetTransformTypeAsString().rfind("CompositeTransform", 0) == 0;
  if (!composite && transforms.size() != 1)
  {
    throw InputError(fileName, "holds " + std::to_string(transforms.size()) +
        " transforms; a registration is one linear transform (a composition is stored as one CompositeTransform)");
  }
  if (composite && transforms.size() == 1)
  {
    throw InputError(fileName, "holds an empty CompositeTransform");
  }
  auto parts = itk::CompositeTransform<double, 3>::New();
  for (auto part = std::next(transforms.begin(), composite ? 1 : 0); part != transforms.end(); ++part)
  {
    // Every part's type was checked to be a linear 3-D one before ITK read the file.
    auto* component = dynamic_cast<Transform3*>(part->GetPointer());
    if (!component)
    {
      throw InputError(fileName, "holds " + (*part)->GetTransformTypeAsString() + ", not a 3-D transform of points");
    }
    parts->AddTransform(component);
  }
  const Transform3* transform = parts.GetPointer();
  // Through the generic interface rather than a cast to a matrix type: every linear type,
  // composites included, is an origin and three axes.
  const auto origin = transform->TransformPoint(Transform3::InputPointType(0.0));
  // Before the axes are taken as differences from it: at 1e30 mm they would cancel to nothing.
  const double translation[3] = { origin[0], origin[1], origin[2] };
  CheckCoordinates(translation, fileName, "the translation");
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
