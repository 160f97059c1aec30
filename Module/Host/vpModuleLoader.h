#ifndef vpModuleLoader_h
#define vpModuleLoader_h

#include "vpLoadableModuleApi.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace vp
{
/// A module path that cannot be used: the message is one line naming the folder or library.
class ModuleLoadError : public std::runtime_error
{
public:
  explicit ModuleLoadError(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

struct LoadedModule
{
  std::string Library; ///< the shared library's path
  const vpModuleDescriptor* Descriptor = nullptr;
};

/// Finds and loads loadable modules the way Slicer loads its qt-loadable-modules: every module
/// library (lib<Name>Module.so; the libraries beside them are not modules) in the folders of the
/// module path is opened and asked for its descriptor.
///
/// Strict on purpose: a library in a module folder that does not open, has no entry point or
/// speaks another API version is an error, not a silent skip, because a clinician's tool that
/// quietly lacks its module is worse than one that says why it will not start. Libraries stay
/// loaded for the life of the process (their descriptors point into them).
class ModuleLoader
{
public:
  /// The module path: explicitPath ("DIR[:DIR...]", from --module-path) when given, else
  /// VP_MODULE_PATH, else the folder beside the program: <exe>/../lib/vesselproximity-modules in
  /// the build tree, <exe>/../lib/Slicer-X.Y/vesselproximity-modules in an installed one (not
  /// qt-loadable-modules, where Slicer would load a *Module library as its Qt plugin).
  static std::vector<std::string> SearchPath(const std::string& explicitPath);

  /// Loads every module in the folders. Throws ModuleLoadError for a missing folder, a library
  /// that fails to open, lacks vpGetLoadableModule or has another API version, two modules of
  /// one name, and a path with no module at all.
  static std::vector<LoadedModule> Load(const std::vector<std::string>& folders);
};
} // namespace vp

#endif
