#include "vpOutputOptions.h"

#include "vpArguments.h"

#include <iostream>

namespace vp
{
namespace
{
cli::Parameter OutputOption(const OutputMethod& method)
{
  return method.ValueName ? Option(cli::ParameterType::String, method.Name, method.Help).SetPlaceholder(method.ValueName)
                          : Switch(method.Name, method.Help);
}
} // namespace

cli::ParameterGroup OutputOptions(OutputOffer offer)
{
  cli::ParameterGroup group{ "Outputs", "", {} };
  for (const OutputMethod& method : FrameOutputMethods())
  {
    if (method.Offered & offer)
    {
      group.Parameters.push_back(OutputOption(method));
    }
  }
  group.Parameters.push_back(Option(cli::ParameterType::File, "sonification",
    "The sound outputs' sonification: a JSON file of voices by level (default: the user guide's table).")
                               .SetChannel(cli::Channel::Input));
  return group;
}

ChosenOutputs::ChosenOutputs(
  const cli::ParsedArguments& args, OutputOffer offer, std::string command, std::vector<std::string> inputs)
  : Command(std::move(command))
  , Sound(args.IsSet("sonification") ? Sonification::Read(args.GetString("sonification")) : Sonification::Default())
{
  inputs.push_back(args.GetString("sonification"));
  for (const OutputMethod& method : FrameOutputMethods())
  {
    const std::string name = OutputOption(method).GetName();
    if (!(method.Offered & offer) || !args.IsSet(name) || (!method.ValueName && !args.GetBoolean(name)))
    {
      continue;
    }
    OutputRequest request;
    request.Source = std::string("--") + method.Name;
    request.Value = method.ValueName ? args.GetString(name) : std::string();
    request.Sound = &this->Sound;
    request.Inputs = inputs;
    const std::string said = this->Command;
    request.Say = [said](const std::string& line) { std::cerr << said + ": " + line + "\n"; };
    this->Made.push_back(method.Make(request));
    this->Outputs.push_back(this->Made.back().get());
  }
}

void ChosenOutputs::SayProblems() const
{
  for (const FrameOutput* output : this->Outputs)
  {
    const std::string problem = output->Problems();
    if (!problem.empty())
    {
      std::cerr << this->Command << ": " << problem << "\n";
    }
  }
}
} // namespace vp
