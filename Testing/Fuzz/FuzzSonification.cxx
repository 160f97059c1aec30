// libFuzzer target for a sonification file (--sonification), which a user writes by hand: any
// JSON must give voices within their documented ranges or be refused with vp::InputError; never
// a crash, a hang or another error. Bytes that are not JSON are the JSON reader's (fuzzed with
// the other JSON files); here they are skipped.
#include "vpInputError.h"
#include "vpSonification.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

namespace
{
bool InRange(const vp::Voice& v)
{
  const auto pitch = [](double hz) { return hz == 0.0 || (hz >= 20.0 && hz <= 20000.0); };
  return pitch(v.PitchHz) && pitch(v.AltPitchHz) && v.BeepsPerSecond >= 0.0 && v.BeepsPerSecond <= 50.0 && v.Duty > 0.0 &&
    v.Duty <= 1.0 && v.Gain >= 0.0 && v.Gain <= 1.0;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const nlohmann::json root = nlohmann::json::parse(data, data + size, nullptr, false);
  if (root.is_discarded())
  {
    return 0;
  }
  try
  {
    const vp::Sonification s = vp::Sonification::FromJson(root, "fuzz.json");
    for (const vp::Voice& v : s.Levels)
    {
      if (!InRange(v))
        __builtin_trap();
    }
    for (const vp::Voice& v : s.Margins)
    {
      if (!InRange(v))
        __builtin_trap();
    }
    if (!InRange(s.Lost))
      __builtin_trap();
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
