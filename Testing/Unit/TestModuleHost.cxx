// The host program and its module path: what --help shows of the loaded module, and the clear
// refusals of a module path that holds no module or a broken one.
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

namespace
{
int CountLines(const std::string& text)
{
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}
} // namespace

TEST(ModuleHost, HelpListsTheLoadedModuleWithItsMetadataAndCommands)
{
  const std::string tmp = vp::test::MakeTempDir("host_help");
  const auto run = vp::test::RunTool(tmp, "--help");
  ASSERT_EQ(run.ExitCode, 0) << run.Err;
  for (const char* expected : { "Vessel Proximity 0.1.0", "category IGT", "module VesselProximity",
         "vesselproximity-modules/", "contributors:", "acknowledgement:", "Noborio", "3D-IRCADb-01" })
  {
    EXPECT_NE(run.Out.find(expected), std::string::npos) << expected << "\n" << run.Out;
  }
  for (const char* command : { "demo", "view", "selftest", "models", "distance", "track", "register", "bench", "phantom" })
  {
    EXPECT_NE(run.Out.find(std::string("\n  ") + command + " "), std::string::npos) << command;
  }
  std::filesystem::remove_all(tmp);
}

// The module a host embeds links neither the phantom generators nor the benchmarks (issue 51):
// those are the demo module's, listed beside it.
TEST(ModuleHost, TheDemoModuleAloneLinksThePhantomAndTheBenchmarks)
{
  const std::string tmp = vp::test::MakeTempDir("host_demo_module");
  const auto help = vp::test::RunTool(tmp, "--help");
  ASSERT_EQ(help.ExitCode, 0) << help.Err;
  EXPECT_NE(help.Out.find("module VesselProximityDemo,"), std::string::npos) << help.Out;
  const std::string lib = std::filesystem::path(VP_EXECUTABLE).parent_path().parent_path().string() + "/lib";
  // What the library needs (readelf's NEEDED lines) and what it defines (nm).
  const auto linked = [&](const std::string& library) {
    const std::string out = tmp + "/linked.txt";
    EXPECT_EQ(std::system(("readelf -d " + library + " >" + out + " && nm -DC --defined-only " + library + " >>" + out).c_str()), 0);
    return vp::test::Slurp(out);
  };
  for (const std::string& library : { lib + "/vesselproximity-modules/libVesselProximityModule.so", lib + "/libVesselProximityCommands.so" })
  {
    const std::string text = linked(library);
    ASSERT_NE(text.find("NEEDED"), std::string::npos) << library << ": " << text.substr(0, 300);
    EXPECT_EQ(text.find("libVesselProximityPhantom"), std::string::npos) << library;
    EXPECT_EQ(text.find("Benchmark"), std::string::npos) << library;
  }
  const std::string demo = linked(lib + "/vesselproximity-modules/libVesselProximityDemoModule.so");
  EXPECT_NE(demo.find("libVesselProximityPhantom"), std::string::npos);
  std::filesystem::remove_all(tmp);
}

TEST(ModuleHost, ModulePathFromTheFlagAndTheEnvironment)
{
  const std::string tmp = vp::test::MakeTempDir("host_path");
  const std::string modules = std::filesystem::path(VP_EXECUTABLE).parent_path().parent_path().string() +
    "/lib/vesselproximity-modules";
  auto run = vp::test::RunTool(tmp, "--module-path " + modules + " phantom -o " + tmp + "/p");
  EXPECT_EQ(run.ExitCode, 0) << run.Err;
  EXPECT_TRUE(vp::test::FileExists(tmp + "/p/portal_vein.stl"));
  // The environment variable is used when there is no flag; an empty folder there is refused.
  std::filesystem::create_directories(tmp + "/empty");
  run = vp::test::RunTool(tmp, "--help", "VP_MODULE_PATH=" + tmp + "/empty");
  EXPECT_EQ(run.ExitCode, 5);
  std::filesystem::remove_all(tmp);
}

TEST(ModuleHost, RefusesAPathWithoutAModule)
{
  const std::string tmp = vp::test::MakeTempDir("host_empty");
  std::filesystem::create_directories(tmp + "/empty");
  auto run = vp::test::RunTool(tmp, "--module-path " + tmp + "/empty --help");
  EXPECT_EQ(run.ExitCode, 5);
  EXPECT_EQ(run.Out, "");
  EXPECT_EQ(CountLines(run.Err), 1) << run.Err;
  EXPECT_NE(run.Err.find(tmp + "/empty: no loadable module there"), std::string::npos) << run.Err;

  run = vp::test::RunTool(tmp, "--module-path " + tmp + "/missing phantom -o " + tmp + "/p");
  EXPECT_EQ(run.ExitCode, 5);
  EXPECT_EQ(CountLines(run.Err), 1) << run.Err;
  EXPECT_NE(run.Err.find(tmp + "/missing: no such folder"), std::string::npos) << run.Err;
  EXPECT_FALSE(vp::test::FileExists(tmp + "/p"));
  std::filesystem::remove_all(tmp);
}

TEST(ModuleHost, RefusesABrokenLibrary)
{
  const std::string tmp = vp::test::MakeTempDir("host_broken");
  // Not an ELF file at all, with a library's name.
  std::filesystem::create_directories(tmp + "/garbage");
  std::ofstream(tmp + "/garbage/libVesselProximityModule.so") << "this is not a shared library\n";
  auto run = vp::test::RunTool(tmp, "--module-path " + tmp + "/garbage --help");
  EXPECT_EQ(run.ExitCode, 5);
  EXPECT_EQ(CountLines(run.Err), 1) << run.Err;
  EXPECT_NE(run.Err.find("libVesselProximityModule.so: cannot load module library"), std::string::npos) << run.Err;

  // A real shared library that is not a module (zlib's), named as modules are; beside a module, a
  // library not so named is not a module (the installed module folder holds the logic library).
  std::filesystem::create_directories(tmp + "/foreign");
  std::filesystem::create_directories(tmp + "/beside");
  bool copied = false;
  for (const char* zlib : { "/usr/lib/x86_64-linux-gnu/libz.so.1", "/lib/x86_64-linux-gnu/libz.so.1", "/usr/lib/libz.so.1" })
  {
    if (vp::test::FileExists(zlib))
    {
      std::filesystem::copy_file(zlib, tmp + "/foreign/libzModule.so");
      std::filesystem::copy_file(zlib, tmp + "/beside/libz.so");
      copied = true;
      break;
    }
  }
  if (copied)
  {
    run = vp::test::RunTool(tmp, "--module-path " + tmp + "/foreign --help");
    EXPECT_EQ(run.ExitCode, 5);
    EXPECT_EQ(CountLines(run.Err), 1) << run.Err;
    EXPECT_NE(run.Err.find("libzModule.so: not a VesselProximity module (no vpGetLoadableModule entry point)"), std::string::npos)
      << run.Err;
    const std::string modules = std::filesystem::path(VP_EXECUTABLE).parent_path().parent_path().string() +
      "/lib/vesselproximity-modules";
    run = vp::test::RunTool(tmp, "--module-path " + tmp + "/beside:" + modules + " --help");
    EXPECT_EQ(run.ExitCode, 0) << run.Err;
    run = vp::test::RunTool(tmp, "--module-path " + tmp + "/beside --help");
    EXPECT_EQ(run.ExitCode, 5);
    EXPECT_NE(run.Err.find("/beside: no loadable module there (lib*Module.so exporting"), std::string::npos) << run.Err;
  }
  else
  {
    std::cout << "[  SKIPPED ] no libz.so.1 found to stand for a foreign library\n";
  }
  std::filesystem::remove_all(tmp);
}

TEST(ModuleHost, UnknownCommandAndMissingModulePathValue)
{
  const std::string tmp = vp::test::MakeTempDir("host_usage");
  auto run = vp::test::RunTool(tmp, "frobnicate");
  EXPECT_EQ(run.ExitCode, 2);
  EXPECT_NE(run.Err.find("unknown command 'frobnicate'"), std::string::npos) << run.Err;
  run = vp::test::RunTool(tmp, "--module-path");
  EXPECT_EQ(run.ExitCode, 2);
  EXPECT_EQ(CountLines(run.Err), 1) << run.Err;
  std::filesystem::remove_all(tmp);
}
