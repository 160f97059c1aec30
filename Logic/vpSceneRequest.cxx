#include "vpSceneRequest.h"

#include "vpClassName.h"
#include "vpInputError.h"
#include "vpVesselLabelTable.h"

namespace vp
{
void CheckVesselClassNames(const std::vector<NamedMesh>& vessels)
{
  const VesselLabelTable table = VesselLabelTable::Default();
  const std::vector<std::string>& known = table.Classes();
  for (const NamedMesh& vessel : vessels)
  {
    const std::string near = NearMissOf(vessel.ClassName, known);
    if (!near.empty())
    {
      throw ParameterError("Vessels", "'" + Printable(vessel.ClassName) + "' is not a known class; did you mean '" + near +
          "'? (a new class needs a name of its own)");
    }
  }
}
} // namespace vp
