#include "vpCliVessels.h"

namespace vp
{
namespace cli
{
const std::vector<VesselClassParameter>& VesselClassParameters()
{
  static const std::vector<VesselClassParameter> classes = {
    { "portalVein", "portal_vein", "Portal vein" },
    { "hepaticArtery", "hepatic_artery", "Hepatic artery" },
    { "hepaticVein", "hepatic_vein", "Hepatic vein" },
  };
  return classes;
}

ParameterGroup VesselModelsGroup()
{
  ParameterGroup models{ "Vessel models", "Surface models of the vessel systems; give at least one", {} };
  for (const VesselClassParameter& v : VesselClassParameters())
  {
    models.Parameters.push_back(Parameter(ParameterType::Geometry, v.Parameter)
                                  .SetTypeAttribute("model")
                                  .SetFileExtensions(".stl,.vtk,.vtp,.obj")
                                  .SetLongFlag(v.Parameter)
                                  .SetLogicName("Vessels")
                                  .SetChannel(Channel::Input)
                                  .SetLabel(v.Label)
                                  .SetDescription(std::string(v.Label) + " surface model (class " + v.ClassName +
                                    "): STL, VTK, VTP or OBJ; a SPACE=RAS/LPS header tag is honoured, untagged "
                                    "files are LPS."));
  }
  return models;
}

Parameter ScalpelModelParameter(const std::string& description)
{
  return Parameter(ParameterType::Geometry, "scalpel")
    .SetTypeAttribute("model")
    .SetFileExtensions(".stl,.vtk,.vtp,.obj")
    .SetLongFlag("scalpel")
    .SetChannel(Channel::Input)
    .SetLabel("Scalpel model")
    .SetDescription(description);
}

std::vector<std::pair<std::string, std::string>> GivenVesselModels(const ParsedArguments& args)
{
  std::vector<std::pair<std::string, std::string>> vessels;
  for (const VesselClassParameter& v : VesselClassParameters())
  {
    if (args.IsSet(v.Parameter))
    {
      vessels.emplace_back(v.ClassName, args.GetString(v.Parameter));
    }
  }
  if (vessels.empty())
  {
    throw UsageError("--portalVein/--hepaticArtery/--hepaticVein", "give at least one vessel model");
  }
  return vessels;
}
} // namespace cli
} // namespace vp
