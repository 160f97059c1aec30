// Registration as IGT tools test it: a known rigid transform, a known tip, recovered from
// synthetic measurements with and without noise (after SlicerIGT's vtkPivotCalibrationTest),
// and ICP of a real instrument surface from a start a few millimetres and degrees off.
#include "vpInputError.h"
#include "vpItkTransformFile.h"
#include "vpPairedPointRegistration.h"
#include "vpPivotCalibration.h"
#include "vpRegistrationFile.h"
#include "vpSurfaceIcpRegistration.h"
#include "vpTestSupport.h"
#include "vtkVesselMeshReader.h"

#include <gtest/gtest.h>

#include <H5Cpp.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <functional>
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

namespace
{
using vp::Matrix4;
/// ITK's LPS <-> Slicer's RAS: x and y negated.
const Matrix4 Flip = { -1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

std::string RefusalOf(const std::function<void()>& read)
{
  try
  {
    read();
  }
  catch (const vp::InputError& e)
  {
    return e.what();
  }
  return "";
}

// A transform as 3D Slicer saved it and showed it (discourse.slicer.org/t/270, "Displayed
// transform vs .tfm content"): the file's numbers in full, the "Transform to parent" matrix the
// Transforms module showed, rounded to two decimals and whole millimetres. The convention read
// from the file must give what Slicer showed: to-parent RAS = F * inverse(file) * F. That
// transform was edited by hand and is not quite orthonormal, so as a registration it is refused.
TEST(SlicerTransformFile, ReadsTheMatrixSlicerShowedAndRefusesItAsNotRigid)
{
  const std::string dir = vp::test::MakeTempDir("slicer_transform_forum");
  const std::string file = vp::test::WriteBytes(dir, "Shown.tfm",
    "#Insight Transform File V1.0\n#Transform 0\nTransform: AffineTransform_double_3_3\n"
    "Parameters: -0.12281062601468536 0.9902729990354874 0.06989222618721933 -0.9559259621663395 -0.0968506562880039 "
    "-0.26898522478338405 -0.2598992353790456 -0.09944665326067206 0.9609182640368552 -64.32660836989362 "
    "-696.1487386450094 -130.6846842169375\nFixedParameters: 0 0 0\n");
  const Matrix4 fromParent = vp::ReadItkLinearTransform(file);
  const Matrix4 shown = vp::MultiplyTransforms(Flip, vp::MultiplyTransforms(vp::InvertTransform(fromParent), Flip));
  const double slicer[12] = { -0.12, -0.96, 0.26, 710, 0.99, -0.1, 0.1, 19, -0.07, 0.27, 0.96, -58 };
  for (int i = 0; i < 12; ++i)
  {
    EXPECT_NEAR(shown[i], slicer[i], i % 4 == 3 ? 0.5 : 0.005) << i;
  }
  const std::string refusal = RefusalOf([&] { vp::ReadTrackerRegistration(file); });
  EXPECT_EQ(refusal.rfind(file + ": the transform is not rigid: the rotation is not orthonormal", 0), 0u) << refusal;
}

// What register and Slicer agree on: the tracker-to-patient a Slicer transform gives is the one
// register's result gives for the same placement, and the four formats ITK writes are read back
// to the last digit that matters.
TEST(SlicerTransformFile, EveryFormatGivesTheRegistrationSlicerMeans)
{
  const std::string dir = vp::test::MakeTempDir("slicer_transform_formats");
  // The patient seen by the tracker (register's model_to_world), tracker numbers taken as RAS.
  const Matrix4 patientToTracker = vp::RotationAboutAxis({ 0.3, -1.0, 0.4 }, 0.7, { 120.0, -35.0, 410.0 });
  // Slicer's node: tracker (its raw numbers, as RAS) to RAS; the patient's RAS is F * its LPS.
  const Matrix4 trackerToRas = vp::MultiplyTransforms(Flip, vp::MultiplyTransforms(vp::InvertTransform(patientToTracker), Flip));
  // What Slicer writes: ITK's LPS, from parent.
  const Matrix4 fileMatrix = vp::MultiplyTransforms(Flip, vp::MultiplyTransforms(vp::InvertTransform(trackerToRas), Flip));
  for (const char* name : { "TrackerToRas.h5", "TrackerToRas.hdf5", "TrackerToRas.tfm", "TrackerToRas.txt" })
  {
    const std::string file = dir + "/" + name;
    vp::WriteItkLinearTransform(file, fileMatrix);
    const Matrix4 read = vp::ReadItkLinearTransform(file);
    for (int i = 0; i < 16; ++i)
    {
      EXPECT_NEAR(read[i], fileMatrix[i], 1e-9) << name << " " << i;
    }
    const vp::TrackerRegistration registration = vp::ReadTrackerRegistration(file);
    EXPECT_EQ(registration.TrackerSpace, vp::PoseSpace::RAS) << name;
    EXPECT_EQ(registration.Kind, "a 3D Slicer transform");
    // A point of the tracker, its raw numbers p: Slicer puts it at trackerToRas * p (RAS); ours
    // reads p as RAS (F * p in LPS) and registers it.
    const vp::Point3 p{ 12.0, -40.0, 33.0 };
    const vp::Point3 ours = vp::TransformPoint(registration.TrackerToPatient, { -p[0], -p[1], p[2] });
    const vp::Point3 slicerRas = vp::TransformPoint(trackerToRas, p);
    EXPECT_NEAR(ours[0], -slicerRas[0], 1e-9) << name;
    EXPECT_NEAR(ours[1], -slicerRas[1], 1e-9) << name;
    EXPECT_NEAR(ours[2], slicerRas[2], 1e-9) << name;
  }
}

// A composite, as ITK writes one (its line, then its parts; applied last part first), of a
// rotation in single precision and a translation: one rigid transform, the parts' product.
TEST(SlicerTransformFile, ACompositeOfLinearPartsIsTheirProduct)
{
  const std::string dir = vp::test::MakeTempDir("slicer_transform_composite");
  const std::string file = vp::test::WriteBytes(dir, "Composite.tfm",
    "#Insight Transform File V1.0\n#Transform 0\nTransform: CompositeTransform_double_3_3\n"
    "#Transform 1\nTransform: AffineTransform_float_3_3\nParameters: 0 -1 0 1 0 0 0 0 1 5 0 0\nFixedParameters: 0 0 0\n"
    "#Transform 2\nTransform: TranslationTransform_double_3_3\nParameters: 1 2 3\nFixedParameters:\n");
  const Matrix4 m = vp::ReadItkLinearTransform(file);
  // Rz90 * (p + (1,2,3)) + (5,0,0): the translation first.
  const Matrix4 expected = { 0, -1, 0, 5 - 2, 1, 0, 0, 1, 0, 0, 1, 3, 0, 0, 0, 1 };
  for (int i = 0; i < 16; ++i)
  {
    EXPECT_NEAR(m[i], expected[i], 1e-6) << i; // the rotation was stored as float
  }
  const std::string empty = vp::test::WriteBytes(dir, "Empty.tfm",
    "#Insight Transform File V1.0\n#Transform 0\nTransform: CompositeTransform_double_3_3\n");
  EXPECT_EQ(RefusalOf([&] { vp::ReadItkLinearTransform(empty); }), empty + ": holds an empty CompositeTransform");
}

TEST(SlicerTransformFile, RefusesWhatIsNoRigidRegistrationInOneLine)
{
  const std::string dir = vp::test::MakeTempDir("slicer_transform_refusals");
  const std::string header = "#Insight Transform File V1.0\n#Transform 0\n";
  const std::string affine = "Transform: AffineTransform_double_3_3\n";
  std::string bspline = header + "Transform: BSplineTransform_double_3_3\nParameters:";
  for (int i = 0; i < 4 * 4 * 4 * 3; ++i)
  {
    bspline += " 0";
  }
  bspline += "\nFixedParameters: 4 4 4 0 0 0 1 1 1 1 0 0 0 1 0 0 0 1\n";
  const std::vector<std::pair<std::pair<std::string, std::string>, std::string>> cases = {
    { { "garbage.tfm", "a registration\n" }, "line 1: expected a comment, Transform:, Parameters: or FixedParameters:" },
    { { "text.h5", header + affine }, "not a transform file ITK can read as h5" },
    { { "short.tfm", header + affine + "Parameters: 1 0 0 0 1 0 0 0 1 0 0\nFixedParameters: 0 0 0\n" },
      "line 3: AffineTransform_double_3_3 takes 12 parameters and 3 fixed ones, the file gives 11 and 3" },
    // What ITK alone took as the identity, and what crashed it (found by fuzz_itk_transform).
    { { "noparameters.tfm", header + affine }, "line 3: AffineTransform_double_3_3 has no Parameters line" },
    { { "nofixed.tfm", header + affine + "Parameters: 1 0 0 0 1 0 0 0 1 0 0 0\n" },
      "line 3: AffineTransform_double_3_3 has no FixedParameters line" },
    { { "translation.tfm", header + "Transform: TranslationTransform_double_3_3\nParameters:\x01\x0fZ 1 2 3\nFixedParameters:\n" },
      "line 4: a control character: not a text transform file" },
    { { "nul.tfm", header + "Transform: TranslationTransform_double_3_3\nParameters: 1" + std::string(3, '\0') + " 2 3\nFixedParameters:\n" },
      "line 4: a control character: not a text transform file" },
    { { "word.tfm", header + "Transform: TranslationTransform_double_3_3\nParameters: 1 2 3mm\nFixedParameters:\n" },
      "line 4: '3mm' is not a finite number" },
    { { "empty.tfm", header + "Transform: TranslationTransform_double_3_3\nParameters:\nFixedParameters:\n" },
      "line 3: TranslationTransform_double_3_3 takes 3 parameters and 0 fixed ones, the file gives 0 and 0" },
    { { "unknown.tfm", header + "Transform: NoSuchTransform_double_3_3\nParameters: 1\nFixedParameters:\n" },
      "line 3: 'NoSuchTransform_double_3_3' is not a transform type ITK knows" },
    { { "twice.tfm", header + affine + "Parameters: 1 0 0 0 1 0 0 0 1 0 0 0\nParameters: 1 0 0 0 1 0 0 0 1 0 0 0\n" },
      "line 5: a second Parameters line for one transform" },
    { { "two.tfm", header + affine + "Parameters: 1 0 0 0 1 0 0 0 1 0 0 0\nFixedParameters: 0 0 0\n#Transform 1\n" + affine +
          "Parameters: 1 0 0 0 1 0 0 0 1 0 0 0\nFixedParameters: 0 0 0\n" },
      "holds 2 transforms; a registration is one linear transform" },
    { { "plane.tfm", header + "Transform: AffineTransform_double_2_2\nParameters: 1 0 0 1 0 0\nFixedParameters: 0 0\n" },
      "holds AffineTransform_double_2_2, not a 3-D transform" },
    { { "warp.tfm", bspline }, "holds BSplineTransform_double_3_3, not a linear transform" },
    { { "scaled.tfm", header + affine + "Parameters: 2 0 0 0 2 0 0 0 2 0 0 0\nFixedParameters: 0 0 0\n" },
      "the transform is not rigid: the rotation is not orthonormal" },
    { { "mirror.tfm", header + affine + "Parameters: -1 0 0 0 1 0 0 0 1 0 0 0\nFixedParameters: 0 0 0\n" },
      "the transform is not rigid: the rotation is a reflection" },
    { { "notanumber.tfm", header + affine + "Parameters: nan 0 0 0 1 0 0 0 1 0 0 0\nFixedParameters: 0 0 0\n" },
      "line 4: 'nan' is not a finite number" },
    { { "R.xml", "<transform/>" }, "not a registration: expected register's RESULT.json or a 3D Slicer transform" },
    { { "far.tfm", header + affine + "Parameters: 1 0 0 0 1 0 0 0 1 1e30 0 0\nFixedParameters: 0 0 0\n" },
      "the translation: coordinate 1e+30 mm is beyond" },
    { { "far.json", "{\"model_to_world\": [1,0,0,0, 0,1,0,2e7, 0,0,1,0, 0,0,0,1]}" },
      "model_to_world's translation: coordinate 2e+07 mm is beyond" },
  };
  for (const auto& [file, expected] : cases)
  {
    const std::string path = vp::test::WriteBytes(dir, file.first, file.second);
    const std::string refusal = RefusalOf([&] { vp::ReadTrackerRegistration(path); });
    ASSERT_FALSE(refusal.empty()) << file.first << " was read";
    EXPECT_EQ(refusal.rfind(path + ": " + expected, 0), 0u) << refusal;
    EXPECT_EQ(refusal.find('\n'), std::string::npos) << refusal;
  }
  const std::string missing = RefusalOf([&] { vp::ReadTrackerRegistration(dir + "/absent.h5"); });
  EXPECT_EQ(missing, dir + "/absent.h5: no such file");
  // The same traps in ITK's HDF5 layout, written through the HDF5 library as ITK lays it out.
  auto hdf5 = [&](const std::string& name, const std::string& type, std::size_t parameters, std::size_t fixed) {
    const std::string path = dir + "/" + name;
    H5::H5File file(path, H5F_ACC_TRUNC);
    file.createGroup("/TransformGroup");
    file.createGroup("/TransformGroup/0");
    const hsize_t one = 1;
    const H5::StrType text(H5::PredType::C_S1, H5T_VARIABLE);
    file.createDataSet("/TransformGroup/0/TransformType", text, H5::DataSpace(1, &one)).write(type, text);
    const std::vector<double> zeros(std::max<std::size_t>(1, std::max(parameters, fixed)), 0.0);
    for (const auto& [set, count] : { std::make_pair("TransformParameters", parameters), std::make_pair("TransformFixedParameters", fixed) })
    {
      const hsize_t n = count;
      file.createDataSet(std::string("/TransformGroup/0/") + set, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &n))
        .write(zeros.data(), H5::PredType::NATIVE_DOUBLE);
    }
    return path;
  };
  const std::string shortH5 = hdf5("short.h5", "TranslationTransform_double_3_3", 1, 0);
  EXPECT_EQ(RefusalOf([&] { vp::ReadTrackerRegistration(shortH5); }),
    shortH5 + ": /TransformGroup/0: TranslationTransform_double_3_3 takes 3 parameters and 0 fixed ones, the file gives 1 and 0");
  const std::string warpH5 = hdf5("warp.h5", "BSplineTransform_double_3_3", 192, 18);
  EXPECT_EQ(RefusalOf([&] { vp::ReadTrackerRegistration(warpH5); }),
    warpH5 + ": holds BSplineTransform_double_3_3, not a linear transform: a registration here is rigid");
  const std::string movedH5 = hdf5("moved.h5", "TranslationTransform_double_3_3", 3, 0);
  EXPECT_EQ(vp::ReadTrackerRegistration(movedH5).TrackerToPatient[3], 0.0) << "counted right, it is read";
}
} // namespace
