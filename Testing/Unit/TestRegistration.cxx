// Registration as IGT tools test it: a known rigid transform, a known tip, recovered from
// synthetic measurements with and without noise (after SlicerIGT's vtkPivotCalibrationTest),
// and ICP of a real instrument surface from a start a few millimetres and degrees off.
#include "vpInputError.h"
#include "vpPairedPointRegistration.h"
#include "vpPivotCalibration.h"
#include "vpSurfaceIcpRegistration.h"
#include "vpTestSupport.h"
#include "vtkVesselMeshReader.h"

#include <gtest/gtest.h>

#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <numeric>
#include <random>

namespace
{
using vp::Point3;
using Matrix = std::array<double, 16>;

Matrix Rigid(Point3 axis, double angleDeg, Point3 translation)
{
  return vp::RotationAboutAxis(axis, vtkMath::RadiansFromDegrees(angleDeg), translation);
}

double Distance(const Point3& a, const Point3& b)
{
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

double TranslationErrorMm(const Matrix& a, const Matrix& b)
{
  return Distance({ a[3], a[7], a[11] }, { b[3], b[7], b[11] });
}

TEST(PairedPointRegistration, RecoversAKnownTransformExactlyAndUnderNoise)
{
  const Matrix truth = Rigid({ 1, 2, -0.5 }, 37.0, { 120.0, -45.0, 300.0 });
  std::mt19937 random(7);
  std::uniform_real_distribution<double> spread(-60.0, 60.0);
  std::vector<Point3> model, world, noisy;
  std::normal_distribution<double> noise(0.0, 0.5); // mm, a typical optical tracker
  for (int i = 0; i < 20; ++i)
  {
    model.push_back({ spread(random), spread(random), spread(random) });
    world.push_back(vp::TransformPoint(truth, model.back()));
    noisy.push_back({ world.back()[0] + noise(random), world.back()[1] + noise(random), world.back()[2] + noise(random) });
  }
  const auto exact = vp::RegisterPairedPoints(model, world);
  EXPECT_LT(vp::RotationBetweenDeg(exact.ModelToWorld, truth), 1e-6);
  EXPECT_LT(TranslationErrorMm(exact.ModelToWorld, truth), 1e-6);
  EXPECT_LT(exact.RmsErrorMm, 1e-6);
  ASSERT_EQ(exact.PointErrorsMm.size(), 20u);

  // 0.5 mm noise, 20 landmarks over 120 mm: rotation within 0.5 degrees, translation within 1 mm;
  // the FRE is about the noise (sigma * sqrt(3 (1 - 2/N)) for a 3D fit: about 0.82 mm).
  const auto fit = vp::RegisterPairedPoints(model, noisy);
  EXPECT_LT(vp::RotationBetweenDeg(fit.ModelToWorld, truth), 0.5);
  EXPECT_LT(TranslationErrorMm(fit.ModelToWorld, truth), 1.0);
  EXPECT_GT(fit.RmsErrorMm, 0.5);
  EXPECT_LT(fit.RmsErrorMm, 1.1);
}

TEST(PairedPointRegistration, RefusesTooFewAndCollinearLandmarks)
{
  const std::vector<Point3> two{ { 0, 0, 0 }, { 1, 0, 0 } };
  EXPECT_THROW(vp::RegisterPairedPoints(two, two), vp::InputError);
  const std::vector<Point3> line{ { 0, 0, 0 }, { 1, 1, 1 }, { 2, 2, 2 }, { 5, 5, 5 } };
  try
  {
    vp::RegisterPairedPoints(line, line);
    ADD_FAILURE() << "collinear landmarks accepted";
  }
  catch (const vp::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("lie on one line"), std::string::npos) << e.what();
  }
}

// Poses of a tool whose tip (in tool coordinates) rests on pivot while the tool swings through
// up to maxAngleDeg in random directions; noiseMm on each tracked position.
std::vector<Matrix> PivotPoses(const Point3& tip, const Point3& pivot, double maxAngleDeg, double noiseMm, int count,
  unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(-maxAngleDeg, maxAngleDeg);
  std::normal_distribution<double> noise(0.0, noiseMm > 0 ? noiseMm : 1.0);
  std::vector<Matrix> poses;
  for (int i = 0; i < count; ++i)
  {
    Matrix m = Rigid({ unit(random), unit(random), 0.2 * unit(random) }, angle(random), { 0, 0, 0 });
    const Point3 rotatedTip = vp::TransformPoint(m, tip);
    for (int k = 0; k < 3; ++k)
      m[4 * k + 3] = pivot[k] - rotatedTip[k] + (noiseMm > 0 ? noise(random) : 0.0);
    poses.push_back(m);
  }
  return poses;
}

TEST(PivotCalibration, FindsAKnownTipWithAndWithoutNoise)
{
  const Point3 tip{ 2.5, -1.0, 160.0 }; // a CUSA handpiece: the tip 16 cm down the shaft
  const Point3 pivot{ 30.0, -80.0, 250.0 };
  const auto exact = vp::CalibratePivot(PivotPoses(tip, pivot, 30.0, 0.0, 100, 1));
  EXPECT_LT(Distance(exact.TipInToolMm, tip), 0.1);
  EXPECT_LT(Distance(exact.PivotInWorldMm, pivot), 0.1);
  EXPECT_LT(exact.RmseMm, 1e-6);
  EXPECT_GT(exact.RotationSpreadDeg, 20.0);

  // With noise sigma on each position, the RMSE follows it (about sigma * sqrt(3)) and the tip
  // error stays within a few sigma for a 30-degree swing of 100 poses.
  for (double sigma : { 0.2, 1.0 })
  {
    const auto noisy = vp::CalibratePivot(PivotPoses(tip, pivot, 30.0, sigma, 100, 2));
    EXPECT_LT(Distance(noisy.TipInToolMm, tip), 3.0 * sigma) << "sigma " << sigma;
    EXPECT_GT(noisy.RmseMm, 0.8 * sigma) << "sigma " << sigma;
    EXPECT_LT(noisy.RmseMm, 2.5 * sigma) << "sigma " << sigma;
  }
}

TEST(PivotCalibration, RefusesTooFewPosesNoRotationAndOneAxis)
{
  const Point3 tip{ 0, 0, 100 }, pivot{ 10, 20, 30 };
  auto message = [](const std::vector<Matrix>& poses) {
    try
    {
      vp::CalibratePivot(poses);
    }
    catch (const vp::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string("calibrated");
  };
  EXPECT_NE(message(PivotPoses(tip, pivot, 30.0, 0.0, 3, 3)).find("too few poses: 3"), std::string::npos);
  EXPECT_NE(message(PivotPoses(tip, pivot, 0.0, 0.3, 50, 4)).find("too little rotation"), std::string::npos);
  // Spinning about the shaft, the tool's own axis through the tip: the tip could be anywhere on it.
  std::vector<Matrix> spin;
  for (int i = 0; i < 20; ++i)
  {
    Matrix m = Rigid({ 0, 0, 1 }, 18.0 * i, { 0, 0, 0 });
    const Point3 t = vp::TransformPoint(m, tip);
    for (int k = 0; k < 3; ++k)
      m[4 * k + 3] = pivot[k] - t[k];
    spin.push_back(m);
  }
  EXPECT_NE(message(spin).find("about one axis only"), std::string::npos) << message(spin);
}

// On the PLUS catalogue's tracked pointer, one ICP from a few millimetres and degrees off. (The
// thin instruments need the multi-start: the next test.)
TEST(SurfaceIcpRegistration, ConvergesOnARealInstrumentFromAFewMillimetresAndDegreesOff)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: the instrument STLs are in ../shared/data/plusmodelcatalog";
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(data + "/plusmodelcatalog/PolarisAscensionPointer.stl");
  reader->Read();
  vtkPolyData* scalpel = reader->GetOutput();
  ASSERT_GT(scalpel->GetNumberOfCells(), 1000);
  const Matrix truth = Rigid({ 0.3, -1, 0.4 }, 65.0, { -40.0, 85.0, 210.0 });
  // 400 surface points as a tracked stylus would digitise them, with 0.1 mm noise.
  std::mt19937 random(11);
  std::uniform_int_distribution<vtkIdType> vertex(0, scalpel->GetNumberOfPoints() - 1);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Point3> measured;
  for (int i = 0; i < 400; ++i)
  {
    Point3 p;
    scalpel->GetPoint(vertex(random), p.data());
    const Point3 w = vp::TransformPoint(truth, p);
    measured.push_back({ w[0] + noise(random), w[1] + noise(random), w[2] + noise(random) });
  }
  // The guess: 3 degrees and 3 mm off.
  const Matrix guess = vp::MultiplyTransforms(Rigid({ 1, 1, 0 }, 3.0, { 2.0, -2.0, 1.0 }), truth);
  const auto fit = vp::RegisterSurfaceIcp(scalpel, measured, guess);
  EXPECT_LT(vp::RotationBetweenDeg(fit.ModelToWorld, truth), 0.3);
  // The tip (the model origin for the PLUS catalogue's instruments) lands within 0.3 mm.
  std::printf("icp: rotation error %g deg, tip error %g mm, residual %g mm, %d iterations\n", vp::RotationBetweenDeg(fit.ModelToWorld, truth),
    Distance(vp::TransformPoint(fit.ModelToWorld, { 0, 0, 0 }), vp::TransformPoint(truth, { 0, 0, 0 })), fit.MeanResidualMm, fit.Iterations);
  EXPECT_LT(Distance(vp::TransformPoint(fit.ModelToWorld, { 0, 0, 0 }), vp::TransformPoint(truth, { 0, 0, 0 })), 0.3);
  EXPECT_LT(fit.MeanResidualMm, 0.15);
  EXPECT_GT(fit.Iterations, 1);
  const double startResidual = vp::RegisterSurfaceIcp(scalpel, measured, guess, 1).MeanResidualMm;
  EXPECT_GT(startResidual, 2.0 * fit.MeanResidualMm) << "the fit improved on the guess";
}
} // namespace
namespace
{
// A thin instrument's ICP problem: 400 of its vertices placed by a random pose, with 0.1 mm noise
// on each coordinate, and a guess 10 degrees (about the tip, its origin) and 10 mm off. Trial k
// of the sequence from one seed, so a hard case can be named and run alone.
struct IcpTrial
{
  Matrix Truth;
  Matrix Guess;
  std::vector<Point3> Measured;
};

IcpTrial MakeIcpTrial(vtkPolyData* tool, int trial)
{
  std::mt19937 random(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<vtkIdType> vertex(0, tool->GetNumberOfPoints() - 1);
  IcpTrial t;
  for (int k = 0; k <= trial; ++k)
  {
    t.Truth = Rigid({ normal(random), normal(random), normal(random) }, 40.0 + 10 * k, { -40.0, 85.0, 210.0 });
    t.Measured.clear();
    for (int i = 0; i < 400; ++i)
    {
      Point3 p;
      tool->GetPoint(vertex(random), p.data());
      const Point3 w = vp::TransformPoint(t.Truth, p);
      t.Measured.push_back({ w[0] + 0.1 * normal(random), w[1] + 0.1 * normal(random), w[2] + 0.1 * normal(random) });
    }
    const Point3 axis{ normal(random), normal(random), normal(random) };
    Point3 shift{ normal(random), normal(random), normal(random) };
    const double length = std::sqrt(shift[0] * shift[0] + shift[1] * shift[1] + shift[2] * shift[2]);
    for (double& s : shift)
    {
      s *= 10.0 / length;
    }
    t.Guess = vp::MultiplyTransforms(t.Truth, Rigid(axis, 10.0, shift));
  }
  return t;
}

// The thin instruments (issue 14): from 10 mm and 10 degrees off, a single ICP slides into wrong
// minima (the PLUS scalpel's tip millimetres up its shaft, the Straizys holder degrees off). The
// multi-start fit must be within 0.5 mm and 0.5 degrees of the truth, or say it does not explain
// the points (and `register icp` refuses it). Scalpel trial 25 and holder trial 11 are the ones
// where the wide starts alone ended in a wrong minimum; the hop to neighbouring minima fits them.
// VP_ICP_TRIALS=40 runs trials 0-39 of each instrument instead: all 80 fitted right (0.37 degrees
// and 0.18 mm at worst), where the wide starts alone fitted 78 and refused 2.
TEST(SurfaceIcpRegistration, ThinInstrumentsFromTenMillimetresAndDegreesOffAreFittedOrRefused)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: the thin instruments' STLs are in ../shared/data";
  struct Instrument
  {
    std::string File;
    std::vector<int> Trials;
  };
  const std::vector<Instrument> instruments = { { data + "/plusmodelcatalog/Scalpel.stl", { 0, 1, 25 } },
    { data + "/straizys-scalpel/scalpel_mech_cutting_tool_assembly.stl", { 0, 1, 3, 11 } } };
  const char* survey = std::getenv("VP_ICP_TRIALS");
  for (const Instrument& instrument : instruments)
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(instrument.File);
    reader->Read();
    vtkPolyData* tool = reader->GetOutput();
    std::vector<int> trials = instrument.Trials;
    if (survey)
    {
      trials.resize(static_cast<std::size_t>(std::max(1, std::atoi(survey))));
      std::iota(trials.begin(), trials.end(), 0);
    }
    int fitted = 0, wrongSingle = 0;
    for (const int trial : trials)
    {
      const IcpTrial t = MakeIcpTrial(tool, trial);
      const auto fit = vp::RegisterSurfaceIcpMultiStart(tool, t.Measured, t.Guess);
      const double rotationDeg = vp::RotationBetweenDeg(fit.ModelToWorld, t.Truth);
      const double tipMm =
        Distance(vp::TransformPoint(fit.ModelToWorld, { 0, 0, 0 }), vp::TransformPoint(t.Truth, { 0, 0, 0 }));
      std::printf("%s, trial %d: %s, %.2f deg, tip %.2f mm, %.1f%% of the points far, %d starts\n", instrument.File.c_str(),
        trial, fit.ExplainsThePoints() ? "fitted" : "refused", rotationDeg, tipMm, 100.0 * fit.FarFraction, fit.Starts);
      if (fit.ExplainsThePoints())
      {
        EXPECT_LE(rotationDeg, 0.5) << instrument.File << ", trial " << trial;
        EXPECT_LE(tipMm, 0.5) << instrument.File << ", trial " << trial;
        ++fitted;
      }
      const auto single = vp::RegisterSurfaceIcp(tool, t.Measured, t.Guess);
      wrongSingle += vp::RotationBetweenDeg(single.ModelToWorld, t.Truth) > 0.5 ? 1 : 0;
    }
    EXPECT_EQ(fitted, static_cast<int>(trials.size())) << instrument.File;
    EXPECT_GE(wrongSingle, 1) << instrument.File << ": these poses should be hard for a single ICP";
  }
}
} // namespace
