#include "vpVesselMeshSet.h"

#include "vpClassName.h"

#include "vpInputError.h"
#include "vpVesselSurface.h"
#include "vtkVesselDistanceEngine.h"
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

std::vector<std::string> DescribeSurfaceDefects(
  vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes, const std::string& repairName)
{
  std::vector<std::string> lines;
  for (const NamedMesh& m : meshes)
  {
    if (m.Repair)
    {
      lines.push_back(m.ClassName + " (" + m.FileName + "): " + repairName + ": " + m.Repair->Describe());
    }
  }
  for (int c = 0; c < engine->GetNumberOfVessels(); ++c)
  {
    const VesselSurface& surface = engine->GetSurface(c);
    if (surface.IsClosed())
    {
      continue;
    }
    std::string file;
    for (const NamedMesh& m : meshes)
    {
      file = m.ClassName == surface.Name() ? m.FileName : file;
    }
    lines.push_back(surface.Name() + " (" + file + "): the surface is not closed (" + surface.Defects().Describe() +
      "): inside is the majority of five rays' crossing parities, and a tip where they disagree is a breach");
  }
  return lines;
}
} // namespace vp
