#ifndef vpSegmentationImport_h
#define vpSegmentationImport_h

#include "vpDicomLabelSeriesReader.h"
#include "vpLabelStructure.h"

#include <string>

namespace vp
{
/// Imports the labelled structures of one input, whatever its form: a folder of DICOM label
/// series (one per structure, or one of several values), a DICOM SEG file, a NRRD, Slicer
/// .seg.nrrd or NIfTI file.
/// wanted decides, by name, which structures' voxels are read where the format allows skipping
/// (the others are listed with null voxels). Throws vp::InputError with one line naming the input.
LabelStructures ImportSegmentation(const std::string& input, const StructureFilter& wanted);

/// Makes, on the calling thread, what the readers' libraries make lazily and without a lock on
/// first use (DCMTK's functional-group factory), so that imports on several threads at once (a
/// cohort's cases) find it made. Call before starting them; more calls do nothing.
void PrepareConcurrentImports();
} // namespace vp

#endif
