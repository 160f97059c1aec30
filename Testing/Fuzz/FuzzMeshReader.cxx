// libFuzzer target for the meshes we hand to VTK's readers (OBJ and legacy VTK: formats we do not
// control), through vtkVesselMeshReader as a user reaches them: any byte string must be read as a
// closed-or-not triangle mesh or refused with vp::InputError; never a crash, a hang or an
// allocation the file merely declares. Built twice: VP_FUZZ_EXTENSION is ".obj" or ".vtk".
#include "vpInputError.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPolyData.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string file = [] {
    vtkObject::GlobalWarningDisplayOff(); // the reader collects VTK's errors itself
    return std::filesystem::temp_directory_path().string() + "/vp_fuzz_" + std::to_string(getpid()) + VP_FUZZ_EXTENSION;
  }();
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(file);
  try
  {
    reader->Read();
    vtkPolyData* mesh = reader->GetOutput();
    if (!mesh || mesh->GetNumberOfPolys() == 0)
    {
      __builtin_trap(); // a read mesh has triangles
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
