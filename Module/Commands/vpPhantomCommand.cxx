// vesselproximity phantom: writes the built-in analytic vessels as STL, for a first run without data.
#include "vpBuiltInPhantom.h"
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vtkVesselMeshWriter.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <iostream>

namespace vp
{
int RunPhantomCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << "usage: vesselproximity phantom -o OUTDIR\n"
                 "  Writes three closed analytic vessels in LPS mm, named for the vessel classes:\n"
                 "  portal_vein.stl (a torus: ring 30 mm, tube 6 mm, centre 0,0,0, axis S),\n"
                 "  hepatic_artery.stl (a capped cylinder: radius 2.5 mm, length 80 mm, centre 0,0,25, axis L),\n"
                 "  hepatic_vein.stl (a sphere: radius 10 mm, centre 45,30,-10).\n";
    return 0;
  }
  const Arguments args(argv, { "-o", "--output" }, {});
  const std::string out = args.Has("-o") ? args.Get("-o") : args.Get("--output");
  if (out.empty())
  {
    throw InputError("-o", "an output folder is required");
  }
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
