#include "vpVesselMeshSet.h"

#include "vpClassName.h"

#include "vpInputError.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>

#include <set>

namespace vp
{
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs)
{
  std::vector<NamedMesh> meshes;
  std::set<std::string> seen;
  for (const auto& pair : pairs)
  {
    const std::string problem = ClassNameProblem(pair.first);
    if (!problem.empty())
    {
      throw ParameterError("Vessels", "'" + Printable(pair.first) + "': " + problem);
    }
    if (!seen.insert(pair.first).second)
    {
      throw ParameterError("Vessels", "class '" + pair.first + "' is given twice");
    }
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(pair.second);
    reader->Read();
    meshes.push_back({ pair.first, pair.second, reader->GetOutput(), std::nullopt });
  }
  return meshes;
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
