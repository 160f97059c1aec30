#include "vtkVesselMeshWriter.h"

#include "vpOutputFile.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <unistd.h>

vtkStandardNewMacro(vtkVesselMeshWriter);

vtkVesselMeshWriter::vtkVesselMeshWriter() = default;
vtkVesselMeshWriter::~vtkVesselMeshWriter() = default;

void vtkVesselMeshWriter::SetInputData(vtkPolyData* mesh)
{
  this->Input = mesh;
  this->Modified();
}

void vtkVesselMeshWriter::Write()
{
  if (!this->Input || this->Input->GetNumberOfPolys() == 0)
  {
    throw vp::InputError(this->FileName, "nothing to write (no triangles)");
  }
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(this->Input);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  vtkPolyData* mesh = triangulate->GetOutput();
  const double sign = this->FileSpace == vp::MeshSpace::RAS ? -1.0 : 1.0;
  std::vector<float> coordinates;
  coordinates.reserve(static_cast<std::size_t>(mesh->GetNumberOfPolys()) * 9);
  auto iter = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    iter->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      double p[3];
      mesh->GetPoints()->GetPoint(ids[k], p);
      coordinates.push_back(static_cast<float>(sign * p[0]));
      coordinates.push_back(static_cast<float>(sign * p[1]));
      coordinates.push_back(static_cast<float>(p[2]));
    }
  }
  const vp::MeshSpace space =
    this->FileSpace == vp::MeshSpace::Unspecified ? vp::MeshSpace::LPS : this->FileSpace;
  vp::WriteFileAtomically(this->FileName, vp::EncodeBinaryStl(coordinates, space));
}

void vtkVesselMeshWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "FileSpace: " << vp::MeshSpaceName(this->FileSpace) << "\n";
  os << indent << "Input triangles: " << (this->Input ? this->Input->GetNumberOfPolys() : 0) << "\n";
}
