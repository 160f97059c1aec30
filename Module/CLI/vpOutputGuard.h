#ifndef vpOutputGuard_h
#define vpOutputGuard_h

#include "vpCliDescription.h"

#include <map>
#include <string>
#include <vector>

namespace vp
{
namespace cli
{
/// Refuses, before any work, a command line whose single-file output would replace one of its
/// inputs: every output file parameter (and the return-parameter file) is compared by device and
/// inode, links followed, with every existing path any other parameter names (lists split at
/// ',' and ';', "NAME=FILE" entries taken by their file). A symbolic link is written through
/// (the link kept) only when it is the user's own or its owner owns its target; two outputs
/// naming one file are refused.
/// Throws vp::InputError naming the output's parameter. Output folders are RunFolder's to guard.
void RefuseOutputsOverInputs(const ModuleDescription& description, const std::map<std::string, std::string>& values,
  const std::map<std::string, std::vector<std::string>>& multiple, const std::string& returnParameterFile);
} // namespace cli
} // namespace vp

#endif
