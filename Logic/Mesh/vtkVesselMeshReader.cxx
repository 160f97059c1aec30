#include "vtkVesselMeshReader.h"

#include "vpPhysicalLimits.h"

#include "vpIndexedMesh.h"
#include "vpLegacyVtkGeometry.h"
#include "vpObjIndices.h"
#include "vpRegularFile.h"
#include "vpStlFormat.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

vtkStandardNewMacro(vtkVesselMeshReader);

namespace
{
std::string LowerExtension(const std::string& fileName)
{
  const std::size_t slash = fileName.find_last_of('/');
  const std::size_t dot = fileName.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return std::string();
  }
  std::string ext = fileName.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

constexpr std::uint64_t StartBytes = 1 << 20;

// The file's bytes, read straight into one string. An STL's first StartBytes are checked
// before the rest is read (vp::CheckStlStart): a gigabyte of zeros or of text is refused at once.
std::string ReadMeshFile(const std::string& fileName, std::uint64_t fileSize, bool stl)
{
  std::ifstream stream(fileName, std::ios::binary);
  if (!stream)
  {
    throw vp::InputError(fileName, std::string("cannot open: ") + std::strerror(errno));
  }
  const auto read = [&](std::string& bytes, std::size_t from) {
    stream.read(&bytes[from], static_cast<std::streamsize>(bytes.size() - from));
    bytes.resize(from + static_cast<std::size_t>(stream.gcount()));
    if (stream.bad())
    {
      throw vp::InputError(fileName, std::string("cannot read: ") + std::strerror(errno));
    }
  };
  std::string bytes(static_cast<std::size_t>(std::min(fileSize, StartBytes)), '\0');
  read(bytes, 0);
  if (stl && fileSize > bytes.size())
  {
    vp::CheckStlStart(bytes.data(), bytes.size(), fileSize, fileName);
  }
  const std::size_t start = bytes.size();
  if (fileSize > start)
  {
    bytes.resize(static_cast<std::size_t>(fileSize));
    read(bytes, start);
  }
  return bytes;
}

/// Collects the first error a VTK reader raises instead of letting it print to the console.
class ErrorCatcher
{
public:
  explicit ErrorCatcher(vtkAlgorithm* algorithm)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(&ErrorCatcher::OnError);
    for (vtkObject* o : { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      o->AddObserver(vtkCommand::ErrorEvent, this->Callback);
      o->AddObserver(vtkCommand::WarningEvent, this->Callback);
    }
  }
  const std::string& Message() const { return this->First; }

private:
  static void OnError(vtkObject*, unsigned long event, void* clientData, void* callData)
  {
    auto* self = static_cast<ErrorCatcher*>(clientData);
    if (event == vtkCommand::ErrorEvent && self->First.empty() && callData)
    {
      std::string message(static_cast<const char*>(callData));
      // VTK messages span lines ("ERROR: In file, line N\nclass: message"): keep the last line.
      while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      {
        message.pop_back();
      }
      const std::size_t newline = message.find_last_of('\n');
      self->First = newline == std::string::npos ? message : message.substr(newline + 1);
      if (self->First.empty())
      {
        self->First = "unreadable";
      }
    }
  }
  vtkNew<vtkCallbackCommand> Callback;
  std::string First;
};

/// Every polygon and strip of a VTK-read polydata names points it has: VTK's readers keep what
/// the file says, and its filters index with it unchecked.
void CheckCellIndices(vtkPolyData* input, const std::string& fileName, bool obj)
{
  const vtkIdType points = input->GetNumberOfPoints();
  for (vtkCellArray* cells : { input->GetPolys(), input->GetStrips() })
  {
    if (!cells)
    {
      continue;
    }
    vtkIdType number = 0;
    auto iter = vtk::TakeSmartPointer(cells->NewIterator());
    for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell(), ++number)
    {
      vtkIdType size;
      const vtkIdType* ids;
      iter->GetCurrentCell(size, ids);
      for (vtkIdType k = 0; k < size; ++k)
      {
        if (ids[k] < 0 || ids[k] >= points)
        {
          // An OBJ index is one-based or relative, and the reader has already turned it into
          // something else: say only that it falls outside.
          throw vp::InputError(fileName, obj
              ? "face " + std::to_string(number + 1) + " names a vertex beyond the " + std::to_string(points) + " defined"
              : std::string(cells == input->GetPolys() ? "polygon " : "strip ") + std::to_string(number + 1) +
                " names point " + std::to_string(ids[k]) + " of " + std::to_string(points));
        }
      }
    }
  }
}

/// A VTK-read polydata's triangles as a soup, so every format goes through one indexing path.
std::vector<double> TriangleSoupFromPolyData(vtkPolyData* input, const std::string& fileName, bool obj)
{
  CheckCellIndices(input, fileName, obj);
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(input);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  vtkPolyData* triangles = triangulate->GetOutput();
  std::vector<double> soup;
  soup.reserve(static_cast<std::size_t>(triangles->GetNumberOfPolys()) * 9);
  auto iter = vtk::TakeSmartPointer(triangles->GetPolys()->NewIterator());
  vtkPoints* points = triangles->GetPoints();
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    iter->GetCurrentCell(size, ids);
    if (size != 3)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      double p[3];
      points->GetPoint(ids[k], p);
      for (double c : p)
      {
        if (!std::isfinite(c))
        {
          throw vp::InputError(fileName, "triangle " + std::to_string(soup.size() / 9 + 1) +
              " has a NaN or infinite coordinate");
        }
        soup.push_back(c);
      }
    }
  }
  return soup;
}

template <typename Reader>
vtkSmartPointer<vtkPolyData> ReadWithVtk(Reader* reader, const std::string& fileName, const char* format)
{
  ErrorCatcher errors(reader);
  reader->SetFileName(fileName.c_str());
  reader->Update();
  if (!errors.Message().empty())
  {
    throw vp::InputError(fileName, std::string("not a readable ") + format + " file (" + errors.Message() + ")");
  }
  vtkPolyData* output = reader->GetOutput();
  if (!output || output->GetNumberOfPoints() == 0)
  {
    throw vp::InputError(fileName, std::string("not a readable ") + format + " file (no points)");
  }
  return output;
}
/// A model's triangles and coordinates within what a patient's model can be.
void CheckModel(vtkPolyData* mesh, const std::string& fileName, std::size_t dropped)
{
  if (mesh->GetNumberOfPolys() == 0)
  {
    throw vp::InputError(fileName,
      dropped ? "every triangle is degenerate (" + std::to_string(dropped) + " dropped)"
              : std::string("no triangles"));
  }
  if (static_cast<double>(mesh->GetNumberOfPolys()) > vp::limits::MaxModelTriangles)
  {
    throw vp::InputError(fileName, std::to_string(mesh->GetNumberOfPolys()) + " triangles: a model holds at most " +
        vp::NumberText(vp::limits::MaxModelTriangles) + " (decimate it first)");
  }
  double bounds[6];
  mesh->GetBounds(bounds);
  for (int i = 0; i < 6; ++i)
  {
    const std::string problem = vp::MagnitudeProblem(bounds[i], vp::limits::CoordinateMm, "mm");
    if (!problem.empty())
    {
      throw vp::InputError(fileName, "a coordinate of " + problem + ": not a patient's model (unit error?)");
    }
  }
}
} // namespace

vtkVesselMeshReader::vtkVesselMeshReader() = default;
vtkVesselMeshReader::~vtkVesselMeshReader() = default;

void vtkVesselMeshReader::SetFileName(const std::string& fileName)
{
  if (fileName != this->FileName)
  {
    this->FileName = fileName;
    this->Modified();
  }
}

vtkSmartPointer<vtkPolyData> vtkVesselMeshReader::ReadThroughVtk(const std::string& bytes, const std::string& ext, std::size_t& dropped)
{
  const std::string& fileName = this->FileName;
  vtkSmartPointer<vtkPolyData> raw;
  if (ext == ".vtk")
  {
    vtkNew<vtkPolyDataReader> reader;
    reader->SetFileName(fileName.c_str());
    if (!reader->IsFilePolyData())
    {
      throw vp::InputError(fileName, "not a legacy VTK polydata file");
    }
    // VTK reads only the geometry we walked first: its reader trusts what a file declares.
    const std::size_t geometry = vp::CheckLegacyVtkGeometry(bytes, fileName);
    reader->ReadFromInputStringOn();
    reader->SetInputString(bytes.data(), static_cast<int>(std::min<std::size_t>(geometry, INT_MAX)));
    raw = ReadWithVtk(reader.Get(), fileName, "legacy VTK");
    this->FileSpace = vp::ParseSpaceTag(reader->GetHeader() ? reader->GetHeader() : "");
  }
  else if (ext == ".vtp")
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    raw = ReadWithVtk(reader.Get(), fileName, "VTP");
    this->FileSpace = vp::ParseSpaceTag(bytes.substr(0, 4096));
  }
  else if (ext == ".obj")
  {
    vp::CheckObjIndices(bytes, fileName);
    vtkNew<vtkOBJReader> reader;
    raw = ReadWithVtk(reader.Get(), fileName, "OBJ");
    this->FileSpace = vp::ParseSpaceTag(bytes.substr(0, 4096));
  }
  else
  {
    throw vp::InputError(fileName,
      "unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : ext) +
        "' (expected .stl, .vtk, .vtp or .obj)");
  }
  const std::vector<double> soup = TriangleSoupFromPolyData(raw, fileName, ext == ".obj");
  return vp::BuildIndexedMesh(soup.data(), soup.size() / 9, &dropped);
}

void vtkVesselMeshReader::Read()
{
  this->Output = nullptr;
  this->FileSpace = vp::MeshSpace::Unspecified;
  this->DegenerateDropped = 0;
  const std::string& fileName = this->FileName;
  if (fileName.empty())
  {
    throw vp::InputError("(no file name)", "no mesh file given");
  }
  const std::string ext = LowerExtension(fileName);
  const std::string bytes = ReadMeshFile(fileName,
    vp::RegularFileSize(fileName, "is a folder, not a mesh file", "is not a regular file (a device, pipe or socket): save the mesh to a file"),
    ext == ".stl");
  if (bytes.empty())
  {
    throw vp::InputError(fileName, "file is empty");
  }

  std::size_t dropped = 0;
  vtkSmartPointer<vtkPolyData> mesh;
  if (ext == ".stl")
  {
    const vp::StlSoup soup = vp::ParseStl(bytes.data(), bytes.size(), fileName);
    this->FileSpace = soup.Space;
    mesh = vp::BuildIndexedMesh(soup.Coordinates.data(), soup.Coordinates.size() / 9, &dropped);
  }
  else
  {
    mesh = this->ReadThroughVtk(bytes, ext, dropped);
  }
  CheckModel(mesh, fileName, dropped);
  const vp::MeshSpace space =
    this->FileSpace == vp::MeshSpace::Unspecified ? this->DefaultFileSpace : this->FileSpace;
  if (space == vp::MeshSpace::RAS)
  {
    // RAS -> LPS is a half turn about the superior axis: orientation (winding) is kept.
    vtkPoints* points = mesh->GetPoints();
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      double p[3];
      points->GetPoint(i, p);
      p[0] = -p[0];
      p[1] = -p[1];
      points->SetPoint(i, p);
    }
  }
  this->DegenerateDropped = static_cast<vtkIdType>(dropped);
  this->Output = mesh;
}

void vtkVesselMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "DefaultFileSpace: " << vp::MeshSpaceName(this->DefaultFileSpace) << "\n";
  os << indent << "FileSpace: " << vp::MeshSpaceName(this->FileSpace) << "\n";
  os << indent << "DegenerateDropped: " << this->DegenerateDropped << "\n";
  os << indent << "Output triangles: " << (this->Output ? this->Output->GetNumberOfPolys() : 0) << "\n";
}
