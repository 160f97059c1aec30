#ifndef vpLabelComponents_h
#define vpLabelComponents_h

#include "vpLabelStructure.h"

namespace vp
{
/// The connected pieces of a structure's voxels (face-connected, as the surface separates them),
/// largest first: one LabelStructure each, on one new grid of the structure's geometry whose
/// values number the pieces (1 the largest). A structure of one piece comes back as it was. A
/// mask of a patient's tumours holds several tumours in one file (IRCADb's livertumor of patient
/// 4): each is a target of its own, with its own margin.
LabelStructures SplitIntoComponents(const LabelStructure& structure);
} // namespace vp

#endif
