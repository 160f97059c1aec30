// libFuzzer target for a models folder's models.json (--tumour DIR, plan --models DIR), which a
// user may have edited or brought from elsewhere: any JSON gives structures whose ids are class
// names and whose files lie beside it, or is refused with vp::InputError; never a crash, a hang
// or another error. Bytes that are not JSON are the JSON reader's (fuzzed with the other JSON
// files); here they are skipped.
#include "vpClassName.h"
#include "vpInputError.h"
#include "vpModelsFile.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const nlohmann::json root = nlohmann::json::parse(data, data + size, nullptr, false);
  if (root.is_discarded())
  {
    return 0;
  }
  try
  {
    const vp::ModelsFile models = vp::ParseModelsFile(root, "/models/models.json");
    for (const vp::ModelStructure& s : models.Structures)
    {
      if (!vp::ClassNameProblem(s.Name).empty() || s.File.rfind("/models/", 0) != 0 || s.File.find("/../") != std::string::npos)
        __builtin_trap();
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
