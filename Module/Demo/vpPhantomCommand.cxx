// vesselproximity phantom: writes the built-in analytic vessels as STL, for a first run without data.
#include "vpBuiltInPhantom.h"
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vtkVesselMeshWriter.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <iostream>

namespace vp
{
cli::ModuleDescription DescribePhantomCommand()
{
  return cli::ModuleDescription::Subcommand("vesselproximity phantom", "write the built-in analytic vessels (STL) for a first run",
    "Writes three closed analytic vessels in LPS mm, named for the vessel classes:\n"
    "  portal_vein.stl (a torus: ring 30 mm, tube 6 mm, centre 0,0,0, axis S),\n"
    "  hepatic_artery.stl (a capped cylinder: radius 2.5 mm, length 80 mm, centre 0,0,25, axis L),\n"
    "  hepatic_vein.stl (a sphere: radius 10 mm, centre 45,30,-10).",
    { { "Output", "", { OutputFolderOption("The folder the three STL files are written into.").SetRequired() } } });
}

int RunPhantomCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  const std::string out = args.GetString("output");
  CreateOutputFolder(out);
  for (const auto& shape : MakeBuiltInVessels())
  {
    vtkNew<vtkVesselMeshWriter> writer;
    writer->SetFileName(out + "/" + shape.first + ".stl");
    writer->SetInputData(shape.second);
    writer->Write();
    std::cout << writer->GetFileName() << "  " << shape.second->GetNumberOfPolys() << " triangles\n";
  }
  return 0;
}
} // namespace vp
