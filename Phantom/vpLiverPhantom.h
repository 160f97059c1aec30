#ifndef vpLiverPhantom_h
#define vpLiverPhantom_h

#include "vpLabelStructure.h"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace vp
{
/// One piece of a vessel centreline: a cone-capsule, the set of points whose distance to the
/// axis segment StartMm-EndMm is at most the radius interpolated at the (clamped) foot of the
/// perpendicular. Consecutive pieces of a branch share their end points, so a branch is a chain
/// of them and a tree is connected wherever pieces meet. LPS millimetres.
struct VesselSegment
{
  std::array<double, 3> StartMm{};
  std::array<double, 3> EndMm{};
  double StartRadiusMm = 0.0;
  double EndRadiusMm = 0.0;
};

/// Settings of the procedural liver phantom. The anatomy (liver shape, vessel trees) does not
/// depend on VoxelMm: only its sampling does, so the centrelines stay the same at any voxel size.
struct LiverPhantomOptions
{
  /// Isotropic voxel size, 0.25-4 mm. At 1 mm the grid is 199 x 149 x 135 (4.0 M voxels); the
  /// 2 mm arteries stay 26-connected up to about 1.2 mm voxels.
  double VoxelMm = 1.0;
  /// Empty space kept around the liver in the grid (0-50 mm). The grid is cropped to the liver:
  /// the vena cava runs on through its top and bottom faces, as a scan's field of view cuts it.
  double MarginMm = 4.0;
  /// Seed of the branching. Any value gives a valid phantom; the default is the one the demo,
  /// its trajectory and the tests are designed on.
  std::uint64_t Seed = 0x5EED1A7E12ULL;
};

/// One structure of the phantom as a mask: voxels 1 inside, 0 outside, on the phantom's grid.
struct PhantomStructure
{
  std::string Name;      ///< folder name, as 3D-IRCADb names its masks: "liver", "portalvein", ...
  std::string ClassName; ///< the class the label table gives that name: liver, portal_vein, ...
  LabelGrid Mask;
};

/// A liver with its three vessel systems, generated from analytic shapes: a blend of deformed
/// ellipsoids for the parenchyma, and branching trees of cone-capsules for the portal vein
/// (12.5 mm trunk at the hilum, Murray's law at every bifurcation, down to 3 mm), the hepatic
/// veins (the inferior vena cava, 22 mm, with right, middle and left trunks of 9-10 mm at their
/// confluence, down to 3 mm) and the hepatic artery (4.5 mm, running beside the portal tree down
/// to 2 mm). Each vessel system is one connected tree; surfaces of different systems are at least
/// MinimumGapMm apart everywhere (analytically; about 1.8 mm guarantees that no voxel of one is
/// a 26-neighbour of a voxel of another at 1 mm voxels).
struct LiverPhantom
{
  /// liver, portalvein, hepaticartery, hepaticvein, in this order, all on one grid.
  std::vector<PhantomStructure> Structures;
  /// The analytic trees per class name (portal_vein, hepatic_artery, hepatic_vein): what the
  /// masks were rasterised from, for trajectory design and tests. The hand-made parts come first,
  /// two segments per branch: portal trunk, right and left branches; artery trunk; vena cava,
  /// then the right, middle and left hepatic trunks. The grown branches follow, three segments
  /// each.
  std::map<std::string, std::vector<VesselSegment>> Centrelines;
  /// The smallest analytic gap between surfaces of different classes (mm).
  static constexpr double MinimumGapMm = 2.0;

  /// The structure of a class name (e.g. "portal_vein"); null when absent.
  const PhantomStructure* FindClass(const std::string& className) const;
};

/// Builds the phantom: deterministic, the same voxels on every machine and compiler (own random
/// generator, no implementation-defined distributions). About 0.3 s at 1 mm voxels. Throws
/// vp::InputError for a voxel size or margin out of range.
LiverPhantom MakeLiverPhantom(const LiverPhantomOptions& options = {});

/// Writes <folder>/<structure name>/image_N, one DICOM series per structure (the layout of
/// 3D-IRCADb's MASKS_DICOM, foreground 255 as in most of its masks), through
/// vp::DicomLabelSeriesWriter. Throws vp::InputError naming the folder.
void WriteLiverPhantomDicom(const LiverPhantom& phantom, const std::string& folder);

/// Signed distance from a point to the analytic surface of one piece: the distance to its axis
/// less the radius interpolated at the foot of the perpendicular (negative inside). Exact for a
/// cylinder piece, within a fraction of a millimetre for the gently tapering pieces here.
double SegmentSignedDistanceMm(const VesselSegment& segment, const std::array<double, 3>& pointMm);

/// The smallest SegmentSignedDistanceMm over a tree: the signed distance to its surface
/// (negative inside); +infinity for an empty tree.
double TreeSignedDistanceMm(const std::vector<VesselSegment>& tree, const std::array<double, 3>& pointMm);
} // namespace vp

#endif
