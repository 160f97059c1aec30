#ifndef vpLoadableModuleApi_h
#define vpLoadableModuleApi_h

/* The contract between the host program `vesselproximity` and a loadable module: plain C, so a
 * module built by another compiler (or a later version of this project) is either understood or
 * refused by its API version, never misread. It plays the part of Slicer's qSlicerLoadableModule
 * plugin interface: the host knows nothing of a module but this descriptor.
 *
 * A module is a shared library exporting
 *     const vpModuleDescriptor* vpGetLoadableModule(void);
 * returning a descriptor that lives as long as the library stays loaded. */

#ifdef __cplusplus
extern "C" {
#endif

#define VP_MODULE_API_VERSION 1
#define VP_MODULE_ENTRY_POINT "vpGetLoadableModule"

/* Runs one command with its arguments (argv[0] is the command name) and returns the process
 * exit code. Errors are reported by the module itself, one line on stderr; nothing may escape
 * as an exception. */
typedef int (*vpModuleCommandFunction)(int argc, const char* const* argv);

typedef struct vpModuleCommand
{
  const char* Name;    /* as typed after the program name: "track" */
  const char* Summary; /* one line for --help */
  vpModuleCommandFunction Run;
} vpModuleCommand;

typedef struct vpModuleDescriptor
{
  int ApiVersion; /* VP_MODULE_API_VERSION of the module's build */
  const char* Name;
  const char* Title;
  const char* Categories;   /* '.'-separated path as Slicer writes it, several separated by ';' */
  const char* Contributors; /* "Name (Affiliation)", separated by ';' */
  const char* HelpText;
  const char* Acknowledgement;
  const char* Version;
  const vpModuleCommand* Commands;
  int NumberOfCommands;
} vpModuleDescriptor;

typedef const vpModuleDescriptor* (*vpGetLoadableModuleFunction)(void);

#ifdef __cplusplus
}
#endif

#endif
