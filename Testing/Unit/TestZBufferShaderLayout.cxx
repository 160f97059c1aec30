// The z-buffer's host structs against its shaders, field by field: every member of a push
// constant block at the offset glslang's reflection gives it in each shader that declares the
// block, every block of the same size, and the storage records at the stride the shader's array
// steps by. A field added, removed or moved on one side only fails here, not in a patient's answer.
#include "vpTestSupport.h"
#include "vpZBufferShaderLayout.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <string>

namespace
{
struct Reflection
{
  std::map<std::string, std::size_t> Offsets; ///< "Parameters.Nx" -> 20
  std::map<std::string, std::size_t> Strides; ///< "Point" -> 16
  std::size_t ParametersSize = 0;             ///< the push constant block's size
};

/// glslangValidator -q on one shader: its reflection, parsed.
Reflection Reflect(const std::string& shader)
{
  const std::string command = std::string(VP_GLSLANG_VALIDATOR) + " -V -q --target-env vulkan1.1 -o /dev/null " +
    VP_SOURCE_DIR + "/Shaders/" + shader + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  EXPECT_TRUE(pipe) << command;
  Reflection r;
  const std::regex member(R"(^([A-Za-z]+\.[A-Za-z]+): offset (\d+),)");
  const std::regex array(R"(^([A-Za-z]+): offset 0, .*arrayStride (\d+),)");
  const std::regex block(R"(^Parameters: offset -1, .* size (\d+),)");
  std::array<char, 512> line{};
  while (pipe && std::fgets(line.data(), line.size(), pipe.get()))
  {
    std::smatch m;
    const std::string text(line.data());
    if (std::regex_search(text, m, member))
    {
      r.Offsets[m[1]] = std::stoul(m[2]);
    }
    else if (std::regex_search(text, m, array))
    {
      r.Strides[m[1]] = std::stoul(m[2]);
    }
    else if (std::regex_search(text, m, block))
    {
      r.ParametersSize = std::stoul(m[1]);
    }
  }
  return r;
}
} // namespace

TEST(ZBufferShaderLayout, EveryFieldSitsWhereEachShaderReadsIt)
{
  std::map<std::string, Reflection> shaders;
  for (const vp::zbuffer::ShaderBlock& block : vp::zbuffer::ShaderBlocks())
  {
    for (const std::string& shader : block.Shaders)
    {
      if (!shaders.count(shader))
      {
        shaders[shader] = Reflect(shader);
        ASSERT_FALSE(shaders[shader].Offsets.empty()) << shader << ": no reflection from glslangValidator";
      }
    }
  }
  std::set<std::pair<std::string, std::string>> checked; // (shader, reflected name)
  for (const vp::zbuffer::ShaderBlock& block : vp::zbuffer::ShaderBlocks())
  {
    const std::string name = block.Block;
    const bool record = name == "PointRecord" || name == "AnswerCeiling" || name == "HostListItem";
    for (const std::string& shader : block.Shaders)
    {
      const Reflection& r = shaders[shader];
      if (!record)
      {
        EXPECT_EQ(r.ParametersSize, block.Size) << block.Block << " in " << shader;
      }
      for (const vp::zbuffer::ShaderField& field : vp::zbuffer::ShaderLayoutFields())
      {
        if (std::string(field.Block) != block.Block)
        {
          continue;
        }
        const auto& table = field.Stride ? r.Strides : r.Offsets;
        const auto it = table.find(field.Name);
        if (it == table.end())
        {
          continue; // this shader does not read it (the per-pixel query reads fewer)
        }
        EXPECT_EQ(it->second, field.Offset) << block.Block << "::" << field.Name << " in " << shader;
        checked.insert({ block.Block, field.Name });
      }
      if (!record)
      {
        for (const auto& [name, offset] : r.Offsets)
        {
          bool declared = false;
          for (const vp::zbuffer::ShaderField& field : vp::zbuffer::ShaderLayoutFields())
          {
            declared = declared || (std::string(field.Block) == block.Block && field.Name == name);
          }
          EXPECT_TRUE(declared) << shader << " reads " << name << " at " << offset << ", which " << block.Block << " does not list";
        }
      }
    }
  }
  // Every host field is read by at least one shader: none is left behind by a shader change.
  for (const vp::zbuffer::ShaderField& field : vp::zbuffer::ShaderLayoutFields())
  {
    EXPECT_TRUE(checked.count({ field.Block, field.Name })) << field.Block << "::" << field.Name << ": no shader reads it";
  }
}
