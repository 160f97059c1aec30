#ifndef vpCliVessels_h
#define vpCliVessels_h

// The scene's models as Slicer hands them to a CLI: one model node per vessel class, each its own
// parameter (a file name is a name, commas and all), and the scalpel's, shared by the programs
// that measure.

#include "vpCliDescription.h"

#include <string>
#include <utility>
#include <vector>

namespace vp
{
namespace cli
{
/// A vessel class: the parameter that brings its model, its class name and its panel label.
struct VesselClassParameter
{
  const char* Parameter;
  const char* ClassName;
  const char* Label;
};

/// Portal vein, hepatic artery, hepatic vein, in the order the answers list them.
const std::vector<VesselClassParameter>& VesselClassParameters();

/// The group of model inputs, one <geometry type="model"> per class.
ParameterGroup VesselModelsGroup();

/// The optional scalpel model input ("scalpel"): the instrument in its own coordinates, its tip
/// and axis found from its shape; description says what it is for in the program.
Parameter ScalpelModelParameter(const std::string& description);

/// The (class, file) of each model given; UsageError when none is.
std::vector<std::pair<std::string, std::string>> GivenVesselModels(const ParsedArguments& args);
} // namespace cli
} // namespace vp

#endif
