#include "vpVesselProximityModule.h"

std::string vpVesselProximityModule::HelpText() const
{
  return "Distance from the tip (and the whole surface) of a tracked CUSA scalpel to the portal vein, the hepatic "
         "artery and the hepatic veins, for liver surgery navigation. Builds vessel surface models from segmented "
         "labelmaps (DICOM series, DICOM SEG, NRRD, .seg.nrrd, NIfTI), registers the scalpel (landmarks, ICP, pivot "
         "calibration) and, for every tracked pose, answers through an exact engine (Embree BVH, double precision) "
         "or the Vulkan z-buffer engine of Noborio et al. with a stated error bound that never understates danger. "
         "Overlays: the scalpel coloured by danger level (white, light gray, dark gray, yellow; magenta inside a vessel), "
         "a line to the closest vessel point with its distance, a readout per vessel class and the distance over "
         "time.";
}

std::string vpVesselProximityModule::AcknowledgementText() const
{
  return "Method: H. Noborio, K. Watanabe, M. Yagi, Y. Ida, S. Nankaku, K. Onishi, M. Koeda, M. Kon, K. Matsui, "
         "M. Kaibori, 'Comparison of GPU-based and CPU-based Algorithms for Determining the Minimum Distance between "
         "a CUSA Scalpel and Blood Vessels', BIOSIGNALS 2016. Data: 3D-IRCADb-01 (IRCAD, Strasbourg; CC BY-NC-ND "
         "4.0), the DICOM SEG examples of dcmqi (QIICR, BSD 3-clause), highdicom and dcmjs (MIT), TotalSegmentator "
         "example labelmaps (Wasserthal et al., Apache 2.0), the PLUS toolkit model catalogue instruments (BSD) "
         "and the Straizys et al. scalpel holder (MIT). Built on VTK, ITK, DCMTK, "
         "Embree, FCL (the whole instrument's reference), Vulkan (Mesa lavapipe), glslang, OpenIGTLink (live tracking), "
         "liblo and libsndfile (sound) and ALSA. Follows the structure of 3D Slicer loadable modules "
         "and of SlicerIGT's BreachWarning module.";
}

