#include "vpCommandSupport.h"

#include "vpInputError.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <set>

namespace vp
{
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs)
{
  std::vector<NamedMesh> meshes;
  std::set<std::string> seen;
  for (const auto& pair : pairs)
  {
    if (!seen.insert(pair.first).second)
    {
      throw InputError("--vessels", "class '" + pair.first + "' is given twice");
    }
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(pair.second);
    reader->Read();
    meshes.push_back({ pair.first, pair.second, reader->GetOutput() });
  }
  return meshes;
}

bool CreateOutputFolder(const std::string& folder)
{
  std::error_code ec;
  const bool created = !std::filesystem::exists(folder, ec);
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder, ec))
  {
    throw InputError(folder, "cannot create folder: " + (ec ? ec.message() : std::string("a file has that name")));
  }
  return created;
}

double NowMs()
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace vp
