// libFuzzer target for tracked sequence headers (PLUS's .igs.mha and .igs.nrrd, which we do not
// control): any byte string must give frames whose transforms are 16 finite numbers, with at
// least one transform name, or be refused with vp::InputError; never a crash or a hang.
#include "vpInputError.h"
#include "vpTrackedSequence.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    const vp::TrackedSequence sequence = vp::ParseTrackedSequence(text, "fuzz");
    if (sequence.Frames.empty() || sequence.TransformNames.empty())
    {
      __builtin_trap();
    }
    for (const auto& frame : sequence.Frames)
    {
      for (const auto& [name, matrix] : frame.Transforms)
      {
        for (const double v : matrix)
        {
          if (!std::isfinite(v))
          {
            __builtin_trap();
          }
        }
      }
    }
    try
    {
      sequence.Resolve("", "fuzz", "tool"); // the default, the only one, or a refusal naming them
    }
    catch (const vp::InputError&)
    {
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
