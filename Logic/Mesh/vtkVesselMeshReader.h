#ifndef vtkVesselMeshReader_h
#define vtkVesselMeshReader_h

#include "vpStlFormat.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>

#include <vtkPolyData.h>

/// Reads a vessel or instrument surface into world (LPS, millimetre) coordinates.
///
/// Formats, chosen by the file name's ending: binary and ASCII STL (.stl), legacy VTK (.vtk),
/// VTK XML polydata (.vtp) and Wavefront OBJ (.obj). The STL parser is our own so that a
/// truncated or lying file is refused instead of read past its end; the others go through VTK's
/// readers with their errors caught.
///
/// Coordinate system: a "SPACE=RAS" or "SPACE=LPS" tag in the header (as 3D Slicer writes it) is
/// honoured and the output is always LPS. A file without a tag is taken to be in
/// DefaultFileSpace (LPS by default, as Slicer has assumed since 4.11).
///
/// The output is an indexed triangle mesh: coincident corners are merged, polygons are
/// triangulated, vertices and lines are ignored, degenerate triangles are dropped and counted.
///
/// Read() throws vp::InputError with a one-line message naming the file and the problem: a
/// missing or empty file, an unknown format, a truncated binary STL, NaN or infinite
/// coordinates, no triangles.
class vtkVesselMeshReader : public vtkObject
{
public:
  static vtkVesselMeshReader* New();
  vtkTypeMacro(vtkVesselMeshReader, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetFileName(const std::string& fileName);
  const std::string& GetFileName() const { return this->FileName; }

  /// Space assumed for files that carry no SPACE tag. Default: LPS.
  void SetDefaultFileSpace(vp::MeshSpace space) { this->DefaultFileSpace = space; }
  vp::MeshSpace GetDefaultFileSpace() const { return this->DefaultFileSpace; }

  /// Reads the file. Throws vp::InputError on bad input; on success GetOutput() holds the mesh.
  void Read();

  vtkPolyData* GetOutput() const { return this->Output; }
  /// The space the file declared (Unspecified when it had no tag).
  vp::MeshSpace GetFileSpace() const { return this->FileSpace; }
  vtkIdType GetNumberOfDegenerateTrianglesDropped() const { return this->DegenerateDropped; }

protected:
  vtkVesselMeshReader();
  ~vtkVesselMeshReader() override;

private:
  /// A VTK, VTP or OBJ file through VTK's reader (after our own checks of it), as triangles.
  vtkSmartPointer<vtkPolyData> ReadThroughVtk(const std::string& bytes, const std::string& ext, std::size_t& dropped);
  vtkVesselMeshReader(const vtkVesselMeshReader&) = delete;
  void operator=(const vtkVesselMeshReader&) = delete;

  std::string FileName;
  vp::MeshSpace DefaultFileSpace = vp::MeshSpace::LPS;
  vp::MeshSpace FileSpace = vp::MeshSpace::Unspecified;
  vtkIdType DegenerateDropped = 0;
  vtkSmartPointer<vtkPolyData> Output;
};

#endif
