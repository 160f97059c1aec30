// Mesh I/O: STL parsing (binary, ASCII, SPACE tag), writing, and the one-line errors.
#include "vpAnalyticShapes.h"
#include "vpIndexedMesh.h"
#include "vpStlFormat.h"
#include "vpTestSupport.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselMeshWriter.h"

#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

namespace
{
using vp::test::WriteBytes;

std::string ReadError(const std::string& path)
{
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(path);
  try
  {
    reader->Read();
  }
  catch (const vp::InputError& e)
  {
    return e.what();
  }
  return std::string();
}

const std::vector<float> TwoTriangles = { 0, 0, 0, 1, 0, 0, 0, 1, 0, /**/ 0, 0, 0, 0, 1, 0, 0, 0, 1 };
} // namespace

TEST(StlFormat, BinaryRoundTripKeepsEveryCoordinateAndTheSpaceTag)
{
  for (vp::MeshSpace space : { vp::MeshSpace::LPS, vp::MeshSpace::RAS })
  {
    std::vector<float> coords = { 1.25f, -3.5f, 100.125f, 7.0f, 8.0f, 9.0f, -0.001f, 2.0f, 1e6f };
    const std::string bytes = vp::EncodeBinaryStl(coords, space);
    ASSERT_EQ(bytes.size(), 84u + 50u);
    EXPECT_EQ(bytes.substr(0, 9), std::string("SPACE=") + vp::MeshSpaceName(space));
    const vp::StlSoup soup = vp::ParseStl(bytes.data(), bytes.size(), "mem");
    EXPECT_EQ(soup.Space, space);
    EXPECT_TRUE(soup.Binary);
    ASSERT_EQ(soup.Coordinates, coords);
  }
}

TEST(StlFormat, WriterAndReaderRoundTripInLpsAndRas)
{
  const std::string dir = vp::test::MakeTempDir("roundtrip");
  const double center[3] = { 12.5, -40.25, 130.0 };
  auto sphere = vp::MakeSphere(center, 7.0, 8, 12);
  for (vp::MeshSpace space : { vp::MeshSpace::LPS, vp::MeshSpace::RAS })
  {
    const std::string path = dir + "/sphere_" + vp::MeshSpaceName(space) + ".stl";
    vtkNew<vtkVesselMeshWriter> writer;
    writer->SetFileName(path);
    writer->SetFileSpace(space);
    writer->SetInputData(sphere);
    writer->Write();
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(path);
    reader->Read();
    EXPECT_EQ(reader->GetFileSpace(), space);
    vtkPolyData* out = reader->GetOutput();
    ASSERT_EQ(out->GetNumberOfPolys(), sphere->GetNumberOfPolys());
    // Coincident corners are merged again: the point count is the original's.
    ASSERT_EQ(out->GetNumberOfPoints(), sphere->GetNumberOfPoints());
    // Every corner of every triangle comes back in LPS as the float the file holds.
    for (vtkIdType t = 0; t < out->GetNumberOfCells(); ++t)
    {
      vtkIdType n1, n2;
      const vtkIdType *ids1, *ids2;
      sphere->GetCellPoints(t, n1, ids1);
      out->GetCellPoints(t, n2, ids2);
      ASSERT_EQ(n2, 3);
      for (int k = 0; k < 3; ++k)
      {
        double a[3], b[3];
        sphere->GetPoint(ids1[k], a);
        out->GetPoint(ids2[k], b);
        for (int axis = 0; axis < 3; ++axis)
        {
          ASSERT_EQ(b[axis], static_cast<double>(static_cast<float>(a[axis]))) << "triangle " << t << " corner " << k;
        }
      }
    }
    // The RAS file really holds RAS coordinates (x and y negated).
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const vp::StlSoup soup = vp::ParseStl(bytes.data(), bytes.size(), path);
    double first[3];
    sphere->GetPoint(0, first);
    const double sign = space == vp::MeshSpace::RAS ? -1.0 : 1.0;
    EXPECT_EQ(soup.Coordinates[0], static_cast<float>(sign * first[0]));
    EXPECT_EQ(soup.Coordinates[2], static_cast<float>(first[2]));
  }
}

TEST(StlFormat, AsciiStlWithSpaceTagIsRead)
{
  const std::string text = "solid SPACE=RAS made by hand\n"
                           "facet normal 0 0 1\n outer loop\n  vertex 1 2 3\n  vertex 4.5 5 6\n  vertex 7 8 9.25e0\n endloop\nendfacet\n"
                           "endsolid\n";
  const vp::StlSoup soup = vp::ParseStl(text.data(), text.size(), "ascii.stl");
  EXPECT_FALSE(soup.Binary);
  EXPECT_EQ(soup.Space, vp::MeshSpace::RAS);
  const std::vector<float> expected = { 1, 2, 3, 4.5f, 5, 6, 7, 8, 9.25f };
  EXPECT_EQ(soup.Coordinates, expected);
}

TEST(StlFormat, BinaryHeaderStartingWithSolidIsStillBinary)
{
  std::string bytes = vp::EncodeBinaryStl(TwoTriangles, vp::MeshSpace::LPS);
  std::memcpy(&bytes[0], "solid exported by a CAD tool", 28);
  const vp::StlSoup soup = vp::ParseStl(bytes.data(), bytes.size(), "cad.stl");
  EXPECT_TRUE(soup.Binary);
  EXPECT_EQ(soup.Coordinates, TwoTriangles);
}

TEST(MeshReader, DegenerateTrianglesAreDroppedAndCounted)
{
  std::vector<float> coords = TwoTriangles;
  const std::vector<float> repeated = { 0, 0, 0, 0, 0, 0, 1, 1, 1 };      // two equal corners
  const std::vector<float> collinear = { 0, 0, 0, 1, 1, 1, 2, 2, 2 };     // zero area
  coords.insert(coords.end(), repeated.begin(), repeated.end());
  coords.insert(coords.end(), collinear.begin(), collinear.end());
  const std::string dir = vp::test::MakeTempDir("degenerate");
  const std::string path = WriteBytes(dir, "d.stl", vp::EncodeBinaryStl(coords, vp::MeshSpace::LPS));
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(path);
  reader->Read();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 2);
  EXPECT_EQ(reader->GetNumberOfDegenerateTrianglesDropped(), 2);
}

TEST(MeshReader, EachBadInputGivesOneLineNamingTheFileAndTheProblem)
{
  const std::string dir = vp::test::MakeTempDir("bad");
  const std::string good = vp::EncodeBinaryStl(TwoTriangles, vp::MeshSpace::LPS);
  std::string overrun = good;
  overrun[80] = 3; // declares 3 triangles, holds 2
  std::vector<float> withNan = TwoTriangles;
  withNan[4] = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> withInf = TwoTriangles;
  withInf[10] = std::numeric_limits<float>::infinity();
  const std::string fifo = dir + "/fifo.stl";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string noTriangles = good.substr(0, 84);
  noTriangles[80] = noTriangles[81] = noTriangles[82] = noTriangles[83] = 0;

  struct Case
  {
    std::string Path;
    std::string Problem;
  };
  const std::vector<Case> cases = {
    { dir + "/missing.stl", "no such file" },
    { WriteBytes(dir, "empty.stl", ""), "file is empty" },
    { WriteBytes(dir, "overrun.stl", overrun), "declares 3 triangles but the file holds only 2" },
    { WriteBytes(dir, "short.stl", good.substr(0, 50)), "too short for a binary STL" },
    { WriteBytes(dir, "nan.stl", vp::EncodeBinaryStl(withNan, vp::MeshSpace::LPS)), "triangle 1 has a NaN or infinite coordinate" },
    { WriteBytes(dir, "inf.stl", vp::EncodeBinaryStl(withInf, vp::MeshSpace::LPS)), "triangle 2 has a NaN or infinite coordinate" },
    { WriteBytes(dir, "none.stl", noTriangles), "no triangles" },
    { WriteBytes(dir, "ascii_none.stl", "solid empty\nendsolid empty\n"), "no triangles" },
    { WriteBytes(dir, "ascii_bad.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2 banana\n"), "line 4: expected three numbers after 'vertex'" },
    { WriteBytes(dir, "ascii_cut.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2 3\nvertex 1 2 4\n"), "ends inside a facet" },
    { WriteBytes(dir, "mesh.ply", "ply\nformat ascii 1.0\n"), "unknown mesh format '.ply'" },
    { WriteBytes(dir, "noext", good), "unknown mesh format '(no extension)'" },
    { WriteBytes(dir, "image.vtk", "# vtk DataFile Version 3.0\nimage\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 1 1 1\n"), "not a legacy VTK polydata file" },
    { WriteBytes(dir, "garbage.vtp", "<VTKFile type=\"PolyData\"> not really"), "not a readable VTP file" },
    { WriteBytes(dir, "lines.vtk", "# vtk DataFile Version 3.0\nl\nASCII\nDATASET POLYDATA\nPOINTS 2 float\n0 0 0 1 1 1\nLINES 1 3\n2 0 1\n"), "no triangles" },
    { WriteBytes(dir, "empty.obj", "# nothing\n"), "not a readable OBJ file" },
    // Indices past the points crashed inside VTK's reader or filters (issue 16); a relative index
    // before the first vertex made up a triangle.
    { WriteBytes(dir, "far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999\n"), "line 4: face names vertex 99999999, but 3 are defined before it" },
    { WriteBytes(dir, "before.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n"), "line 4: face names vertex -5, but 3 are defined before it" },
    { WriteBytes(dir, "notcoords.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"), "line 4: face names texture coordinate 1, but 0 are defined before it" },
    { WriteBytes(dir, "nonormal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n"), "line 5: face names normal 2, but 1 are defined before it" },
    { WriteBytes(dir, "slash.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nvn 0 0 -1\nf 1//1 3//1 2/ 4\n"),
      "line 6: face entry '2/' is not v, v/vt, v//vn or v/vt/vn" },
    { WriteBytes(dir, "mixed.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nf 1//1 3 2//1\n"),
      "line 5: face entry '3' is not of the same form as the first" },
    { WriteBytes(dir, "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), "line 4: face entry '0' is not a nonzero whole-number index" },
    { WriteBytes(dir, "far.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 7000000\n"),
      "polygon 1 names point 7000000 of 3" },
    { WriteBytes(dir, "huge.vtk", "# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 2000000000 float\n"),
      "POINTS declares 2000000000 values, more than the file's 77 bytes can hold" },
    { WriteBytes(dir, "cells.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 400000000\n3 0 1 2\n"),
      "POLYGONS declares 400000000 values, more than the file's" },
    { WriteBytes(dir, "overrun.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n5 0 1 2 0\n"),
      "POLYGONS: cell 1 declares 5 points, past the section's 4 values" },
    { WriteBytes(dir, "offsets.vtk", "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 3\nOFFSETS vtktypeint64\n0 7\nCONNECTIVITY vtktypeint64\n0 1 2\n"),
      "POLYGONS: offset 2 (7) does not run from 0 up to the connectivity's 3" },
    { WriteBytes(dir, "fewpoints.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 8 float\n0 0 0 1 0 0 0 1 0 0 0 1\nPOLYGONS 1 4\n3 0 1 2\n"),
      "POINTS: value 13 of 24 is 'POLYGONS', not a number" },
    { WriteBytes(dir, "shortpoints.vtk", "# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 3 float\n\0\0\0\0"),
      "POINTS ends past the end of the file" },
    // fuzz_vtk_reader: a binary section whose header line runs on to the end of the file made
    // VTK's reader read from the stream it had closed (a null pointer).
    { WriteBytes(dir, "runon.vtk", std::string("# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 1 float\n") +
        std::string(12, '\0') + "\nPOLYGONS 0 0 vtkCompos" + std::string(6, '\0') + "# vtk?"),
      "POLYGONS: its header line does not end before its binary values" },
    { WriteBytes(dir, "field.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nFIELD FieldData 1\nw 1 1 float\n1\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"),
      "field data before the geometry is not read" },
    // Not regular files: /dev/zero never ends, a FIFO with no writer never opens.
    { "/dev/zero", "is not a regular file" },
    { fifo, "is not a regular file" },
    { WriteBytes(dir, "strip.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nTRIANGLE_STRIPS 1 5\n4 0 1 2 3\n"),
      "strip 1 names point 3 of 3" },
  };
  for (const Case& c : cases)
  {
    const std::string message = ReadError(c.Path);
    EXPECT_EQ(message.rfind(c.Path + ": ", 0), 0u) << "names the file: " << message;
    EXPECT_NE(message.find(c.Problem), std::string::npos) << c.Path << " -> " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

// A gigabyte of zeros named .stl, and a gigabyte whose second line is not STL (issue 16): refused
// from the file's first megabyte, before the rest is read (each was read whole first, 2.1 GB of
// memory and 17 s for the zeros). The files are sparse: they take no disk.
TEST(MeshReader, AGigabyteOfZerosOrOfTextIsRefusedFromItsStart)
{
  const std::string dir = vp::test::MakeTempDir("huge");
  const auto sparse = [&](const std::string& name, const std::string& start) {
    const std::string path = dir + "/" + name;
    {
      std::ofstream(path, std::ios::binary) << start;
    }
    EXPECT_EQ(truncate(path.c_str(), off_t(1) << 30), 0);
    return path;
  };
  const std::string zeros = sparse("zeros.stl", "");
  const std::string text = sparse("text.stl", "solid garbage\nthis is not a facet\n" + std::string(100, ' ') + "\n");
  struct rusage before = {};
  getrusage(RUSAGE_SELF, &before);
  const auto start = std::chrono::steady_clock::now();
  const std::string zeroError = ReadError(zeros);
  const std::string textError = ReadError(text);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  struct rusage after = {};
  getrusage(RUSAGE_SELF, &after);
  std::printf("both refused in %.3f s, peak memory %ld -> %ld kB\n", seconds, before.ru_maxrss, after.ru_maxrss);
  EXPECT_EQ(zeroError, zeros + ": STL file has no triangles");
  EXPECT_EQ(textError, text + ": line 2: unexpected 'this' in ASCII STL");
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64L * 1024L) << "kB: neither file was read whole";
}

TEST(MeshReader, VtkVtpAndObjAreReadAsTheSameTriangles)
{
  const std::string dir = vp::test::MakeTempDir("formats");
  const std::string vtk = WriteBytes(dir, "t.vtk",
    "# vtk DataFile Version 3.0\nSPACE=RAS two triangles\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n"
    "0 0 0 1 0 0 0 1 0 0 0 1\nPOLYGONS 2 8\n3 0 1 2\n3 0 2 3\n");
  const std::string obj = WriteBytes(dir, "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n");
  const std::string vtp = WriteBytes(dir, "t.vtp",
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
    "<Piece NumberOfPoints=\"4\" NumberOfPolys=\"1\">\n<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
    "0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>\n<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>"
    "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray></Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n");
  for (const std::string& path : { vtk, obj, vtp })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(path);
    reader->Read();
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 2) << path; // the VTP quad is triangulated
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 4) << path;
  }
  // The legacy VTK header's SPACE=RAS is honoured: x and y come back negated (LPS).
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(vtk);
  reader->Read();
  EXPECT_EQ(reader->GetFileSpace(), vp::MeshSpace::RAS);
  double p[3];
  reader->GetOutput()->GetPoint(1, p);
  EXPECT_EQ(p[0], -1.0);
}

TEST(MeshReader, IrcadbReferenceMeshesAreRead)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: IRCADb mesh reading not tested";
  }
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(extracted + "/ircadb/3Dircadb1.1/MESHES_VTK/portalvein.vtk");
  reader->Read();
  // The data README counts 19,737 triangles in patient 1's portal vein.
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys() + reader->GetNumberOfDegenerateTrianglesDropped(), 19737);
  EXPECT_EQ(reader->GetFileSpace(), vp::MeshSpace::Unspecified);
}

TEST(MeshReader, RealInstrumentStlIsRead)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: real STL reading not tested";
  }
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(data + "/plusmodelcatalog/Scalpel.stl");
  reader->Read();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys() + reader->GetNumberOfDegenerateTrianglesDropped(), 27190);
}
