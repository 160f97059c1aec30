#ifndef vpOutputOptions_h
#define vpOutputOptions_h

// The outputs a front end offers on request (the registry vp::FrameOutputMethods), as options
// declared once: --osc, --audio, --audio-wav and --sonification where the front end offers them.

#include "vpCliDescription.h"
#include "vpFrameOutputFactory.h"
#include "vpSonification.h"

#include <memory>
#include <string>
#include <vector>

namespace vp
{
/// The "Outputs" group: each output the front end offers (offer: its OutputOffer bit), and the
/// sonification file its sound outputs share.
cli::ParameterGroup OutputOptions(OutputOffer offer);

/// The outputs the command line asks for, made before any frame (a bad value, or a file output
/// that would replace one of the run's inputs, throws InputError naming the option); they live
/// as long as this.
class ChosenOutputs
{
public:
  /// command: what the lines said start with ("live"); inputs: the files the run reads (the
  /// sonification file is added).
  ChosenOutputs(
    const cli::ParsedArguments& args, OutputOffer offer, std::string command, std::vector<std::string> inputs = {});
  ChosenOutputs(const ChosenOutputs&) = delete;
  ChosenOutputs& operator=(const ChosenOutputs&) = delete;

  /// In the registry's order; add each to the session, the recorder or the view.
  const std::vector<FrameOutput*>& Get() const { return this->Outputs; }
  /// After the run: each output's problem (FrameOutput::Problems), a line on stderr.
  void SayProblems() const;

private:
  std::string Command;
  Sonification Sound;
  std::vector<std::unique_ptr<FrameOutput>> Made;
  std::vector<FrameOutput*> Outputs;
};
} // namespace vp

#endif
