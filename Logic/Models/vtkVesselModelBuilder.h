#ifndef vtkVesselModelBuilder_h
#define vtkVesselModelBuilder_h

#include "vpLabelStructure.h"

#include <vtkObject.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <vector>

/// Builds the closed surface model of one vessel class (or the liver) from labelled voxels, the
/// way 3D Slicer's binary-labelmap-to-closed-surface conversion does: the union of the
/// structures' voxels, cropped to their extent and padded by one empty voxel so the surface
/// closes at the volume's edge, discrete flying edges, optional decimation (vtkDecimatePro,
/// topology kept), windowed-sinc smoothing on the voxel grid, then the index-to-LPS transform and
/// outward normals: flying edges winds every triangle alike, so the surface is turned as a whole
/// where the transform reflects (a cavity's wall faces into the cavity). The output is triangles
/// in LPS millimetres (the DICOM frame).
///
/// Smoothing follows Slicer: factor f gives a pass band of 10^(-4 f) over SmoothingIterations
/// iterations, with boundary and feature-edge smoothing off and non-manifold smoothing on. More
/// iterations or a larger factor shrink thin vessels.
class vtkVesselModelBuilder : public vtkObject
{
public:
  static vtkVesselModelBuilder* New();
  vtkTypeMacro(vtkVesselModelBuilder, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Smoothing factor, 0 (none) to 1. Default 0.5, Slicer's default.
  vtkSetClampMacro(SmoothingFactor, double, 0.0, 1.0);
  vtkGetMacro(SmoothingFactor, double);
  /// Windowed-sinc iterations. Default 20, as Slicer.
  vtkSetClampMacro(SmoothingIterations, int, 1, 1000);
  vtkGetMacro(SmoothingIterations, int);
  /// Fraction of triangles to remove, 0 (none, the default as in Slicer) to 0.99.
  vtkSetClampMacro(DecimationFactor, double, 0.0, 0.99);
  vtkGetMacro(DecimationFactor, double);

  /// The surface of the union of the structures' voxels. Structures on different grids are
  /// meshed each on its own grid and the surfaces appended. Throws vp::InputError naming the
  /// source when the structures hold no voxel.
  vtkSmartPointer<vtkPolyData> Build(const std::vector<const vp::LabelStructure*>& structures);

  /// Voxels in the last model built (on all its grids).
  vtkGetMacro(NumberOfVoxels, vtkIdType);
  /// Volume of those voxels (mm^3): what the surface should enclose, give or take smoothing.
  vtkGetMacro(VoxelVolumeMm3, double);

protected:
  vtkVesselModelBuilder() = default;
  ~vtkVesselModelBuilder() override = default;

private:
  vtkVesselModelBuilder(const vtkVesselModelBuilder&) = delete;
  void operator=(const vtkVesselModelBuilder&) = delete;

  vtkSmartPointer<vtkPolyData> BuildOnGrid(const std::vector<const vp::LabelStructure*>& structures);
  /// The contour decimated and smoothed as the settings say (each when its factor is above 0).
  vtkSmartPointer<vtkPolyData> DecimateAndSmooth(vtkPolyData* contour) const;

  double SmoothingFactor = 0.5;
  int SmoothingIterations = 20;
  double DecimationFactor = 0.0;
  vtkIdType NumberOfVoxels = 0;
  double VoxelVolumeMm3 = 0.0;
};

#endif
