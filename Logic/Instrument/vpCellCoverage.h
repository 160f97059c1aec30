#ifndef vpCellCoverage_h
#define vpCellCoverage_h

namespace vp
{
/// Of the cube of edge 1 centred at the origin, the fraction where n·y <= offset (n a unit
/// vector): the closed form over the cube's corners (inclusion–exclusion of the corner
/// tetrahedra); exact, or within 1e-6 for a plane within a thousandth of square to an axis.
double CubeFractionBelowPlane(const double n[3], double offset);

/// A solid's wall near a lattice cell, taken as a plane: the points y with
/// OutwardNormal·(y - centre) < OffsetMm are inside. OffsetMm is the cell centre's depth (its
/// distance to the wall, negative outside); the normal is the wall's outward direction at its
/// nearest point. A wall bent across the cell is off by its bend (a sphere of radius R: about
/// edge² / 8R); a cell counted by its centre alone is off by up to all of it.
struct WallPlane
{
  double OutwardNormal[3] = { 0, 0, 1 };
  double OffsetMm = 0.0;
};

/// The share of the cell (centre, edge cellMm) inside the solid behind wall: closed form.
double CellShareInside(const WallPlane& wall, double cellMm);
/// The share of the cell inside both solids, where both walls cross it (a product of the two
/// shares is wrong there: a tip face on the vessel wall, its normal opposite, shares nothing).
/// Exact along the cell's third axis, on 8 x 8 columns across the other two.
double CellShareInsideBoth(const WallPlane& a, const WallPlane& b, double cellMm);
} // namespace vp

#endif
