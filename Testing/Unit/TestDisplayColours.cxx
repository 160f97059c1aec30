// The colours a clinician reads meaning from, computed from the colours the code uses: a danger
// level never looks like a vessel class (CIELAB distance), a class has one colour everywhere, and
// the readout's text reads on the view's background (WCAG contrast).
#include "vpDangerBands.h"
#include "vpDangerLevels.h"
#include "vpVesselLabelTable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
/// The default table's classes, then four classes it does not know (palette colours).
std::vector<std::pair<std::string, vp::Rgb>> ClassColours()
{
  std::vector<std::pair<std::string, vp::Rgb>> colours;
  int index = 0;
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  for (const std::string& name : table.Classes())
  {
    colours.emplace_back(name, vp::ClassDisplayColour(name, index++));
  }
  for (const char* other : { "tumour", "bile_duct", "gallbladder", "cava_graft" })
  {
    colours.emplace_back(other, vp::ClassDisplayColour(other, index++));
  }
  return colours;
}

vp::Rgb LevelColour(int level)
{
  return vp::DangerLevelColour(static_cast<vp::DangerLevel>(level));
}
} // namespace

TEST(DisplayColours, CieLabIsTheStandardOne)
{
  const auto white = vp::CieLab({ 255, 255, 255 });
  EXPECT_NEAR(white[0], 100.0, 0.01);
  EXPECT_NEAR(white[1], 0.0, 0.01);
  EXPECT_NEAR(white[2], 0.0, 0.01);
  const auto red = vp::CieLab({ 255, 0, 0 }); // the published sRGB red: L* 53.24, a* 80.09, b* 67.20
  EXPECT_NEAR(red[0], 53.24, 0.05);
  EXPECT_NEAR(red[1], 80.09, 0.05);
  EXPECT_NEAR(red[2], 67.20, 0.05);
  EXPECT_NEAR(vp::CieLabDistance({ 0, 0, 0 }, { 255, 255, 255 }), 100.0, 0.01);
}

// The paper's danger blue was the hepatic veins' (15 apart) and its breach red the artery's (13).
TEST(DisplayColours, NoDangerLevelLooksLikeAVesselClass)
{
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  const std::vector<std::string> known = table.Classes();
  for (int level = 0; level < vp::NumberOfDangerLevels; ++level)
  {
    for (const auto& [name, colour] : ClassColours())
    {
      const double distance = vp::CieLabDistance(LevelColour(level), colour);
      const bool tableClass = std::find(known.begin(), known.end(), name) != known.end();
      EXPECT_GE(distance, tableClass ? 40.0 : 20.0)
        << vp::DangerLevelName(static_cast<vp::DangerLevel>(level)) << " against " << name;
    }
    for (int other = level + 1; other < vp::NumberOfDangerLevels; ++other)
    {
      EXPECT_GE(vp::CieLabDistance(LevelColour(level), LevelColour(other)), 20.0)
        << vp::DangerLevelName(static_cast<vp::DangerLevel>(level)) << " against "
        << vp::DangerLevelName(static_cast<vp::DangerLevel>(other));
    }
  }
}

TEST(DisplayColours, ATumourLooksLikeNoVesselAndNoLevel)
{
  for (int level = 0; level < vp::NumberOfDangerLevels; ++level)
  {
    EXPECT_GE(vp::CieLabDistance(LevelColour(level), vp::TumourDisplayColour), 40.0)
      << vp::DangerLevelName(static_cast<vp::DangerLevel>(level));
  }
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  for (const std::string& name : table.Classes())
  {
    if (table.RoleOf(name) == vp::ModelRole::Tumour)
    {
      // The table's tumour class is drawn as every tumour is.
      EXPECT_LT(vp::CieLabDistance(vp::ClassDisplayColour(name, 0), vp::TumourDisplayColour), 1.0) << name;
      continue;
    }
    EXPECT_GE(vp::CieLabDistance(vp::ClassDisplayColour(name, 0), vp::TumourDisplayColour), 40.0) << name;
  }
}

// One colour per class: the label table's, as the scene's models take it (the plot and the
// readout take ClassDisplayColour too: before, the hepatic vein was violet in the plot).
TEST(DisplayColours, AClassHasTheLabelTablesColour)
{
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  for (const auto& [name, colour] : ClassColours())
  {
    const auto& classes = table.Classes();
    if (std::find(classes.begin(), classes.end(), name) == classes.end())
    {
      continue;
    }
    const auto fraction = table.Color(name);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(colour[k], std::lround(255 * fraction[k])) << name;
    }
  }
}

// Every readout line reads on the view: WCAG contrast 4.5 or more against both ends of its
// background (the hepatic vein's dark blue, lifted halfway to white as before, was 3.4).
TEST(DisplayColours, TheReadoutsTextReadsOnTheView)
{
  for (const auto& [name, colour] : ClassColours())
  {
    const vp::Rgb text = vp::ReadoutTextColour(colour);
    EXPECT_GE(vp::ContrastRatio(text, vp::ViewBackgroundTop), 4.5) << name;
    EXPECT_GE(vp::ContrastRatio(text, vp::ViewBackgroundBottom), 4.5) << name;
  }
  EXPECT_LT(vp::ContrastRatio({ 128, 157, 217 }, vp::ViewBackgroundTop), 4.5) << "the old hepatic vein line";
}
