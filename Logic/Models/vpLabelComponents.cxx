#include "vpLabelComponents.h"

#include <vtkImageConnectivityFilter.h>
#include <vtkNew.h>

namespace vp
{
LabelStructures SplitIntoComponents(const LabelStructure& structure)
{
  if (!structure.Grid.Labels)
  {
    return { structure };
  }
  vtkNew<vtkImageConnectivityFilter> pieces;
  pieces->SetInputData(structure.Grid.Labels);
  // A one-structure mask (value 0 here) is every non-zero voxel; a multi-label volume, its value.
  const double lo = structure.LabelValue == 0 ? 1.0 : structure.LabelValue;
  const double hi = structure.LabelValue == 0 ? 65535.0 : structure.LabelValue;
  pieces->SetScalarRange(lo, hi);
  pieces->SetExtractionModeToAllRegions();
  pieces->SetLabelModeToSizeRank();
  pieces->SetLabelScalarTypeToUnsignedShort();
  pieces->GenerateRegionExtentsOff();
  pieces->Update();
  const int count = pieces->GetNumberOfExtractedRegions();
  if (count <= 1)
  {
    return { structure };
  }
  LabelGrid grid = structure.Grid;
  grid.Labels = vtkSmartPointer<vtkImageData>::New();
  grid.Labels->ShallowCopy(pieces->GetOutput());
  LabelStructures out;
  for (int k = 1; k <= count; ++k)
  {
    LabelStructure piece = structure;
    piece.Grid = grid;
    piece.LabelValue = k;
    piece.OnlyValue = false;
    piece.Piece = k;
    piece.PieceCount = count;
    out.push_back(piece);
  }
  return out;
}
} // namespace vp
