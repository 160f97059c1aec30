#include "vpDefaultScalpel.h"

#include "CusaHandpiece_json.h"
#include "CusaHandpiece_stl.h"
#include "vpInputError.h"
#include "vtkVesselMeshWriter.h"

#include <filesystem>

namespace vp
{

std::string WriteDefaultScalpel(const std::string& folder)
{
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
  {
    throw InputError(folder, "cannot create folder: " + ec.message());
  }
  const std::string stl = folder + "/CusaHandpiece.stl";
  WriteFileAtomically(stl, std::string(reinterpret_cast<const char*>(CusaHandpiece_stl), CusaHandpiece_stl_size));
  WriteFileAtomically(
    folder + "/CusaHandpiece.json", std::string(reinterpret_cast<const char*>(CusaHandpiece_json), CusaHandpiece_json_size));
  return stl;
}
} // namespace vp
