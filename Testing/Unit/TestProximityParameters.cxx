// The parameter set and the logic that observes it: an event only on a change, a rebuild only
// for a change of what the engines are built from, and the per-frame settings applied at once.
#include "vpAnalyticShapes.h"
#include "vpInputError.h"
#include "vtkExactVesselDistance.h"
#include "vtkScalpelModel.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityParameters.h"
#include "vtkZBufferVesselDistance.h"
#include "vpVulkanTestSupport.h"

#include <gtest/gtest.h>

#include <vtkCallbackCommand.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cmath>
#include <functional>

namespace
{
const double Origin[3] = { 0, 0, 0 };

int CountModified(vtkObject* object, const std::function<void()>& change)
{
  int count = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&count);
  counter->SetCallback([](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
  const unsigned long tag = object->AddObserver(vtkCommand::ModifiedEvent, counter);
  change();
  object->RemoveObserver(tag);
  return count;
}

vp::TrackedPose TipAt(double x)
{
  return { 0.0, { 1, 0, 0, x, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 } };
}

class ProximityParameters : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const double z[3] = { 0, 0, 1 }, centre[3] = { 0, 0, -20 };
    this->Scalpel->SetModel(vp::MakeCappedCylinder(centre, z, 1.0, 40.0, 12));
    this->Parameters->SetVessel("portal_vein", this->Sphere);
    this->Parameters->SetScalpel(this->Scalpel);
    this->Parameters->SetComputeSurfaceDistance(false);
    this->Logic->SetParameters(this->Parameters);
  }
  vtkSmartPointer<vtkPolyData> Sphere = vp::MakeSphere(Origin, 10.0, 30, 60);
  vtkNew<vtkScalpelModel> Scalpel;
  vtkNew<vtkVesselProximityParameters> Parameters;
  vtkNew<vtkVesselProximityLogic> Logic;
};

TEST_F(ProximityParameters, FireAnEventOnlyWhenAValueChanges)
{
  vtkVesselProximityParameters* p = this->Parameters;
  EXPECT_EQ(CountModified(p, [&] { p->SetVessel("portal_vein", this->Sphere); }), 0);
  EXPECT_EQ(CountModified(p, [&] { p->SetScalpel(this->Scalpel); }), 0);
  EXPECT_EQ(CountModified(p, [&] { p->SetHysteresisMm(0.3); }), 0);
  EXPECT_EQ(CountModified(p, [&] { p->SetFrameBudgetMs(16.7); }), 0);
  EXPECT_EQ(CountModified(p, [&] { p->SetDangerThresholds(vp::DangerThresholds()); }), 0);
  EXPECT_EQ(CountModified(p, [&] { p->SetComputeSurfaceDistance(false); }), 0);
  EXPECT_EQ(CountModified(p, [&] { p->SetHysteresisMm(0.5); }), 1);
  EXPECT_EQ(CountModified(p, [&] { p->SetCompareWithExact(true); }), 1);
  EXPECT_EQ(CountModified(p, [&] { p->SetVessel("hepatic_vein", vp::MakeSphere(Origin, 3.0, 10, 20)); }), 1);
  EXPECT_THROW(p->SetHysteresisMm(-1.0), vp::ParameterError);
  EXPECT_THROW(p->SetFrameBudgetMs(std::nan("")), vp::ParameterError);
  try
  {
    p->SetFrameBudgetMs(-1.0);
    ADD_FAILURE() << "a negative budget was taken";
  }
  catch (const vp::ParameterError& e)
  {
    EXPECT_EQ(e.GetParameter(), "FrameBudgetMs") << "named as the logic knows it, not as a flag";
  }
}

TEST_F(ProximityParameters, TheLogicRebuildsForTheSceneAndNeverForASetting)
{
  this->Logic->ProcessPose(TipAt(15.0));
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 1);
  EXPECT_NEAR(this->Logic->GetLastFrame().Proximity.Classes[0].DistanceMm, 5.0, 0.05);
  EXPECT_EQ(this->Logic->GetLastFrame().Level, vp::DangerLevel::Warning);

  // Thresholds, hysteresis and budget: applied to the next frame, nothing rebuilt.
  vp::DangerThresholds wide;
  wide.CautionMm = 30.0;
  wide.WarningMm = 20.0;
  wide.DangerMm = 8.0;
  this->Parameters->SetDangerThresholds(wide);
  this->Parameters->SetHysteresisMm(0.0);
  this->Parameters->SetFrameBudgetMs(0.0);
  this->Logic->ProcessPose(TipAt(15.0));
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 1);
  EXPECT_EQ(this->Logic->GetLastFrame().Level, vp::DangerLevel::Danger);
  EXPECT_EQ(this->Logic->GetTrackingLogic()->GetHysteresisMm(), 0.0);
  EXPECT_EQ(this->Logic->GetTrackingLogic()->GetFrameBudgetMs(), 0.0);

  // A new vessel surface, a new engine, a new switch: one rebuild each, on the next frame.
  this->Parameters->SetVessel("portal_vein", vp::MakeSphere(Origin, 12.0, 30, 60));
  this->Logic->ProcessPose(TipAt(15.0));
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 2);
  EXPECT_NEAR(this->Logic->GetLastFrame().Proximity.Classes[0].DistanceMm, 3.0, 0.05);
  this->Parameters->SetDistanceEngine(vtkSmartPointer<vtkExactVesselDistance>::New());
  this->Logic->ProcessPose(TipAt(16.0));
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 3);
  this->Logic->ProcessPose(TipAt(17.0)); // the scalpel moved: nothing rebuilt
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 3);

  // Another parameter set: the logic follows it and no longer hears the first.
  vtkNew<vtkVesselProximityParameters> other;
  other->SetVessel("hepatic_vein", this->Sphere);
  other->SetScalpel(this->Scalpel);
  other->SetComputeSurfaceDistance(false);
  this->Logic->SetParameters(other);
  this->Logic->ProcessPose(TipAt(15.0));
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 4);
  EXPECT_EQ(this->Logic->GetLastFrame().Proximity.Classes[0].ClassName, "hepatic_vein");
  this->Parameters->SetHysteresisMm(1.0);
  this->Parameters->SetVessel("portal_vein", this->Sphere);
  this->Logic->ProcessPose(TipAt(15.0));
  EXPECT_EQ(this->Logic->GetNumberOfBuilds(), 4);
  EXPECT_EQ(this->Logic->GetTrackingLogic()->GetHysteresisMm(), 0.3);
}

// With the z-buffer engine, the logic builds the query's ceilings when it builds the engines, so
// that no frame pays for them (tens to hundreds of milliseconds on large layers): the first
// frame's query already starts from them and dispatches a few of the range's tiles.
TEST_F(ProximityParameters, TheLogicBuildsTheZBuffersCeilingsBeforeAnyFrame)
{
  VP_REQUIRE_VULKAN();
  auto zbuffer = vtkSmartPointer<vtkZBufferVesselDistance>::New();
  this->Parameters->SetDistanceEngine(zbuffer);
  this->Logic->ProcessPose(TipAt(12.0));
  EXPECT_NEAR(this->Logic->GetLastFrame().Proximity.Classes[0].DistanceMm, 2.0, zbuffer->GetErrorBoundMm() + 0.05);
  EXPECT_GT(zbuffer->GetCeilingBuildTimeMs(), 0.0);
  EXPECT_LT(zbuffer->GetLastQueryTiles() * 5, zbuffer->GetLastQueryTilesInRange());
}
} // namespace
