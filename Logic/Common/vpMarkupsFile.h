#ifndef vpMarkupsFile_h
#define vpMarkupsFile_h

#include <array>
#include <string>
#include <vector>

namespace vp
{
/// One control point of a 3D Slicer markups point list.
struct MarkupsPoint
{
  std::string Label;
  std::string Description;
  std::array<double, 3> PositionLps{ 0.0, 0.0, 0.0 };
};

/// The defined control points of a 3D Slicer point list file, in LPS, in file order: a markups
/// JSON file (.mrk.json, .json: the first markup's "controlPoints", in its "coordinateSystem",
/// LPS when absent, as Slicer reads them) or a fiducial CSV (.fcsv: "# Markups fiducial file
/// version = ..." and "# CoordinateSystem = RAS|LPS|0|1" before rows "id,x,y,z,...,label,...").
/// Points whose positionStatus is not "defined" are left out. Throws InputError naming the file
/// and the place for anything else: no control point, a position that is not three numbers within
/// limits::CoordinateMm, an unknown coordinate system, an fcsv without its version line (Slicer
/// would read it as the Slicer 3 layout), a file of over 16 MB.
std::vector<MarkupsPoint> ReadMarkupsPoints(const std::string& fileName);
/// The same from text; fcsv tells the layout (fuzzing, tests).
std::vector<MarkupsPoint> ParseMarkupsPoints(const std::string& text, bool fcsv, const std::string& source);

/// The text of a markups JSON point list ("type": "Fiducial", LPS) that 3D Slicer loads as a
/// point list node; each point's label and description as given.
std::string MarkupsJsonText(const std::vector<MarkupsPoint>& points);
} // namespace vp

#endif
