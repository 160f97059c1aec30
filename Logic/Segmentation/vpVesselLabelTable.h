#ifndef vpVesselLabelTable_h
#define vpVesselLabelTable_h

#include "vpLabelStructure.h"
#include "vpModelRole.h"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace vp
{
/// Maps imported structures to the vessel classes (portal_vein, hepatic_vein, hepatic_artery)
/// and to liver. The default table is Resources/VesselLabels.json, compiled into the library; it
/// knows the names found in our data (IRCADb's portalvein, portalvein1, venoussystem, venacava,
/// artery, liver), SNOMED codes as DICOM SEG and Slicer carry them, and TotalSegmentator's label
/// ids. A structure matches by coded type first, then by name (case, '_' and '-' ignored), then,
/// only when the labelmap had no names ("label N") or held one value under its file's name (a
/// mask, a temporary file Slicer wrote), by value. A name matches a listed name with or without a
/// number after it ("Tumor 2", "lesion_3"); a name the table does not list matches a class one of
/// whose name_contains words it holds (IRCADb's "livertumor03"); a name holding one of a class's
/// name_excludes words (an adrenal "leftsurretumor", a "metastasectomie") is never that class by
/// name. Each class has a role: a vessel class is one model, measured against; a tumour
/// class one model per structure and connected piece; the liver is shown.
class VesselLabelTable
{
public:
  /// The compiled-in Resources/VesselLabels.json.
  static VesselLabelTable Default();
  /// A table in the same format; throws vp::InputError naming the file on any problem.
  static VesselLabelTable Load(const std::string& fileName);
  static VesselLabelTable Parse(const std::string& json, const std::string& source);

  /// The class of a structure, or "" when the table does not know it.
  std::string ClassOf(const LabelStructure& structure) const;
  /// The class a name maps to, or "": decides which structures are worth reading.
  std::string ClassOfName(const std::string& name) const;

  /// A class's role ("role" in the table; default vessel, liver for the class "liver" and tumour
  /// for "tumour"); Vessel for a class the table does not have.
  ModelRole RoleOf(const std::string& className) const;

  /// Classes in table order.
  const std::vector<std::string>& Classes() const { return this->ClassNames; }
  /// Display colour (RGB, 0..1) of a class; grey for an unknown one.
  std::array<double, 3> Color(const std::string& className) const;

private:
  std::vector<std::string> ClassNames;
  std::map<std::string, std::string> ByName, ByCode;
  std::map<int, std::string> ByValue;
  std::map<std::string, std::array<double, 3>> Colors;
  std::map<std::string, ModelRole> Roles;
  std::vector<std::pair<std::string, std::string>> ByNamePart; ///< (word, class), in table order
  std::map<std::string, std::vector<std::string>> Excludes;    ///< per class, words that keep a name out of it
  /// Whether a name (normalized, blanks out) holds one of the class's name_excludes words.
  bool Excluded(const std::string& squeezed, const std::string& className) const;
};
} // namespace vp

#endif
