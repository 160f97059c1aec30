#ifndef vtkVesselMeshWriter_h
#define vtkVesselMeshWriter_h

#include "vpStlFormat.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>

#include <vtkPolyData.h>

/// Writes a surface held in LPS millimetres as binary STL, with "SPACE=LPS" (default) or
/// "SPACE=RAS" in the 80-byte header as 3D Slicer writes it; with RAS the coordinates are
/// converted on the way out. Polygons are triangulated. The file appears whole or not at all:
/// it is written under a temporary name in the same folder and renamed.
/// Write() throws vp::InputError naming the file when it cannot be written.
class vtkVesselMeshWriter : public vtkObject
{
public:
  static vtkVesselMeshWriter* New();
  vtkTypeMacro(vtkVesselMeshWriter, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetFileName(const std::string& fileName) { this->FileName = fileName; }
  const std::string& GetFileName() const { return this->FileName; }
  void SetInputData(vtkPolyData* mesh);
  /// Space the file is written in. Default: LPS.
  void SetFileSpace(vp::MeshSpace space) { this->FileSpace = space; }
  vp::MeshSpace GetFileSpace() const { return this->FileSpace; }

  void Write();

protected:
  vtkVesselMeshWriter();
  ~vtkVesselMeshWriter() override;

private:
  vtkVesselMeshWriter(const vtkVesselMeshWriter&) = delete;
  void operator=(const vtkVesselMeshWriter&) = delete;

  std::string FileName;
  vp::MeshSpace FileSpace = vp::MeshSpace::LPS;
  vtkSmartPointer<vtkPolyData> Input;
};


#endif
