// The scalpel model: its tip found automatically on real instrument models, given in a JSON file
// beside the model or on the command line, and placed in the world by a pose.
#include "vpAnalyticShapes.h"
#include "vpDefaultScalpel.h"
#include "vpInputError.h"
#include "vpScalpelLoader.h"
#include "vpScalpelTipFinder.h"
#include "vpModelTestSupport.h"
#include "vpTestSupport.h"
#include "vtkScalpelModel.h"
#include "vtkVesselMeshReader.h"

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cmath>
#include <fstream>

namespace
{
double AngleToDeg(const double a[3], const double b[3])
{
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::acos(std::max(-1.0, std::min(1.0, dot))) * 180.0 / M_PI;
}

std::string PlusModel(const std::string& name)
{
  const std::string data = vp::test::TestDataDir();
  return data.empty() ? std::string() : data + "/plusmodelcatalog/" + name;
}

/// A symmetric instrument: a capped shaft of radius 1 mm from z = -100 to 0.
vtkSmartPointer<vtkPolyData> MakeToyInstrument()
{
  const double z[3] = { 0, 0, 1 };
  const double shaftCentre[3] = { 0, 0, -50 };
  return vp::MakeCappedCylinder(shaftCentre, z, 1.0, 100.0, 24);
}
} // namespace

// The PLUS catalogue puts the tip of its straight instruments at the origin with the shaft along
// -z: the finder must find that end, without being told, to about a millimetre.
TEST(ScalpelTipFinder, FindsTheTipOfRealInstrumentsAtTheirOrigin)
{
  if (vp::test::TestDataDir().empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: no instrument STLs (plusmodelcatalog)";
  }
  const double plusZ[3] = { 0, 0, 1 };
  struct Case
  {
    const char* File;
    double TipToleranceMm;
  };
  // The needle's model reaches 1.1 mm beyond its catalogue origin (the bevel's point).
  for (const Case c : { Case{ "Scalpel.stl", 0.5 }, Case{ "Cautery.stl", 0.5 }, Case{ "Needle_BardDuaLok57.stl", 1.2 },
         Case{ "Stylus_100mm.stl", 0.5 } })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(PlusModel(c.File));
    reader->Read();
    const vp::ScalpelTipEstimate e = vp::FindScalpelTip(reader->GetOutput(), c.File);
    const double distance = std::sqrt(e.TipMm[0] * e.TipMm[0] + e.TipMm[1] * e.TipMm[1] + e.TipMm[2] * e.TipMm[2]);
    EXPECT_LT(distance, c.TipToleranceMm) << c.File << ": " << e.Description;
    EXPECT_LT(AngleToDeg(e.Axis.data(), plusZ), 5.0) << c.File << ": " << e.Description;
    EXPECT_FALSE(e.Ambiguous) << c.File << ": " << e.Description;
    EXPECT_LT(e.TipEndAreaMm2, 0.8 * e.OtherEndAreaMm2) << c.File;
    EXPECT_NE(e.Description.find("found automatically"), std::string::npos);
  }
}

TEST(ScalpelTipFinder, SaysWhenTheEndsAreAlike)
{
  const vp::ScalpelTipEstimate e = vp::FindScalpelTip(MakeToyInstrument(), "toy");
  EXPECT_TRUE(e.Ambiguous);
  EXPECT_NE(e.Description.find("guess"), std::string::npos);
  EXPECT_NEAR(e.LengthMm, 100.0, 1e-6);
  EXPECT_LT(std::min(std::abs(e.TipMm[2]), std::abs(e.TipMm[2] + 100.0)), 0.3); // one of the two ends
}

TEST(ScalpelTipFinder, RefusesAModelWithoutSurface)
{
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(vp::FindScalpelTip(empty, "empty.stl"), vp::InputError);
}

TEST(ScalpelModel, PlacesTipAndAxisByThePose)
{
  vtkNew<vtkScalpelModel> scalpel;
  scalpel->SetTipMm(0, 0, 5);
  scalpel->SetAxis(0, 0, 2); // normalised
  // 90 degrees about x (y -> z, z -> -y), then (10, 20, 30).
  scalpel->SetModelToWorld({ 1, 0, 0, 10, 0, 0, -1, 20, 0, 1, 0, 30, 0, 0, 0, 1 });
  double tip[3], axis[3];
  scalpel->GetTipInWorld(tip);
  scalpel->GetAxisInWorld(axis);
  EXPECT_DOUBLE_EQ(tip[0], 10.0);
  EXPECT_DOUBLE_EQ(tip[1], 15.0);
  EXPECT_DOUBLE_EQ(tip[2], 30.0);
  EXPECT_DOUBLE_EQ(axis[0], 0.0);
  EXPECT_DOUBLE_EQ(axis[1], -1.0);
  EXPECT_DOUBLE_EQ(axis[2], 0.0);
  EXPECT_THROW(scalpel->SetAxis(0, 0, 0), vp::InputError);
}

class ScalpelLoader : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("scalpel");
    this->Model = vp::test::WriteMeshFile(this->Dir, "Toy.stl", MakeToyInstrument());
  }
  void WriteDefinition(const std::string& text)
  {
    std::ofstream(this->Dir + "/Toy.json") << text;
  }
  std::string Dir, Model;
};

TEST_F(ScalpelLoader, DefinitionBesideTheModelIsUsedAndNamed)
{
  this->WriteDefinition(R"({"tip_mm": [0, 0, -100], "axis": [0, 0, -1], "note": "handle end, for the test"})");
  auto scalpel = vp::LoadScalpel(this->Model, {});
  EXPECT_DOUBLE_EQ(scalpel->GetTipMm()[2], -100.0);
  EXPECT_DOUBLE_EQ(scalpel->GetAxis()[2], -1.0);
  EXPECT_NE(scalpel->GetTipSource().find("Toy.json"), std::string::npos) << scalpel->GetTipSource();
  EXPECT_GT(scalpel->GetModel()->GetNumberOfPolys(), 0);
}

TEST_F(ScalpelLoader, GivenTipWinsAndGetsThePrincipalAxisTowardsIt)
{
  this->WriteDefinition(R"({"tip_mm": [0, 0, -100]})");
  vp::ScalpelTipDefinition given;
  given.TipMm = std::array<double, 3>{ 0, 0, 0 };
  given.Source = "--tip";
  auto scalpel = vp::LoadScalpel(this->Model, given);
  EXPECT_DOUBLE_EQ(scalpel->GetTipMm()[2], 0.0);
  EXPECT_NEAR(scalpel->GetAxis()[2], 1.0, 1e-9); // from the centre (z = -50) towards z = 0
  EXPECT_NE(scalpel->GetTipSource().find("--tip"), std::string::npos);
  given.TipMm = std::array<double, 3>{ 0, 0, -100 };
  EXPECT_NEAR(vp::LoadScalpel(this->Model, given)->GetAxis()[2], -1.0, 1e-9);
}

TEST_F(ScalpelLoader, WithoutDefinitionTheFinderDecidesAndSaysSo)
{
  auto scalpel = vp::LoadScalpel(this->Model, {});
  EXPECT_NE(scalpel->GetTipSource().find("found automatically"), std::string::npos);
  EXPECT_LT(std::min(std::abs(scalpel->GetTipMm()[2]), std::abs(scalpel->GetTipMm()[2] + 100.0)), 0.3);
}

TEST_F(ScalpelLoader, BadDefinitionFilesAreRefusedByName)
{
  for (const char* text : { "{not json", R"({"axis": [0, 0, 1]})", R"({"tip_mm": [0, 0]})", R"({"tip_mm": [0, "a", 0]})",
         R"({"tip_mm": [0, 0, 0], "axis": [0, 0, 0]})", "[1, 2, 3]" })
  {
    this->WriteDefinition(text);
    try
    {
      vp::LoadScalpel(this->Model, {});
      ADD_FAILURE() << "accepted: " << text;
    }
    catch (const vp::InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find("Toy.json"), std::string::npos) << e.what();
    }
  }
}

// The built-in handpiece from memory is the handpiece its written files give, point for point.
TEST(DefaultScalpel, FromMemoryIsTheWrittenOneReadBack)
{
  const auto written = vp::LoadScalpel(vp::WriteDefaultScalpel(vp::test::MakeTempDir("default-scalpel")), {});
  const auto inMemory = vp::MakeDefaultScalpel();
  vtkPolyData* a = written->GetModel();
  vtkPolyData* b = inMemory->GetModel();
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  ASSERT_EQ(a->GetNumberOfPolys(), b->GetNumberOfPolys());
  EXPECT_EQ(b->GetNumberOfPolys(), 1824);
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(a->GetPoint(i)[c], b->GetPoint(i)[c]) << "point " << i;
    }
  }
  EXPECT_EQ(written->GetTipSource(), inMemory->GetTipSource());
  EXPECT_EQ(inMemory->GetAxis()[2], 1.0);
  vp::ScalpelTipDefinition given;
  given.TipMm = std::array<double, 3>{ 0, 0, -10 };
  given.Axis = std::array<double, 3>{ 0, 1, 0 };
  const auto moved = vp::MakeDefaultScalpel(given);
  EXPECT_EQ(moved->GetTipMm()[2], -10.0);
  EXPECT_EQ(moved->GetAxis()[1], 1.0);
}
