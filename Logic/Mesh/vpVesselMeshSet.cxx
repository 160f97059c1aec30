#include "vpVesselMeshSet.h"

#include "vpClassName.h"

#include "vpInputError.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>

#include <set>

namespace vp
{
std::vector<NamedMesh> LoadVesselMeshes(std::vector<NamedMesh> vessels)
{
  std::set<std::string> seen;
  for (NamedMesh& vessel : vessels)
  {
    const std::string problem = ClassNameProblem(vessel.ClassName);
    if (!problem.empty())
    {
      throw ParameterError("Vessels", "'" + Printable(vessel.ClassName) + "': " + problem);
    }
    if (!seen.insert(vessel.ClassName).second)
    {
      throw ParameterError("Vessels", "class '" + vessel.ClassName + "' is given twice");
    }
    if (!vessel.Mesh)
    {
      vtkNew<vtkVesselMeshReader> reader;
      reader->SetFileName(vessel.FileName);
      reader->Read();
      vessel.Mesh = reader->GetOutput();
    }
  }
  return vessels;
}

std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs)
{
  std::vector<NamedMesh> vessels;
  for (const auto& pair : pairs)
  {
    vessels.push_back({ pair.first, pair.second, nullptr, std::nullopt });
  }
  return LoadVesselMeshes(std::move(vessels));
}

std::vector<NamedMesh> LoadTumourMeshes(std::vector<NamedMesh> tumours)
{
  std::set<std::string> seen;
  for (NamedMesh& tumour : tumours)
  {
    const std::string problem = ClassNameProblem(tumour.ClassName); // it is a column's value and a JSON key
    if (!problem.empty())
    {
      throw ParameterError("Tumours", "tumour id '" + Printable(tumour.ClassName) + "' (" + Printable(tumour.FileName) +
          "): " + problem);
    }
    if (!seen.insert(tumour.ClassName).second)
    {
      throw ParameterError("Tumours", "tumour '" + Printable(tumour.ClassName) + "' is given twice");
    }
    if (!tumour.Mesh)
    {
      vtkNew<vtkVesselMeshReader> reader;
      reader->SetFileName(tumour.FileName);
      reader->Read();
      tumour.Mesh = reader->GetOutput();
    }
  }
  return tumours;
}

void RepairVesselMeshes(std::vector<NamedMesh>& meshes)
{
  for (NamedMesh& m : meshes)
  {
    vtkNew<vtkVesselSurfaceRepair> repair;
    repair->SetInputData(m.Mesh);
    repair->Update();
    m.Mesh = repair->GetOutput();
    m.Repair = repair->GetReport();
  }
}
} // namespace vp
