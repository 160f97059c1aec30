#ifndef vpFrameHeadline_h
#define vpFrameHeadline_h

#include "vpTrackedFrame.h"

#include <string>

namespace vp
{
/// "portal_vein" -> "portal vein": class names are identifiers, headlines are for people.
std::string ReadableClassName(std::string name);

/// The vessels' part of a headline, the frame's level and its cause in words: "BREACH: instrument
/// 1.0 mm into the hepatic vein", "DANGER: tip 1.2 mm from the portal vein", "SAFE".
std::string DescribeDanger(const TrackedFrame& frame);

/// The margin's part: "MARGIN VIOLATED: tumour 03, 1.7 mm", "INSIDE TUMOUR: tumour 03, 2.1 mm in",
/// "MARGIN NEAR: tumour 03, 6.2 mm", "MARGIN CLEAR"; empty without tumours.
std::string DescribeMargin(const TrackedFrame& frame);

/// Whether the margin's level is more severe than the vessels': near ranks with a warning,
/// violated with danger, inside with a breach; on a tie the vessels win (a cut vessel bleeds now).
bool MarginOutranksDanger(const TrackedFrame& frame);

/// What a headline says of a frame: the most severe of the vessels' level and the margin's, with
/// its cause (DescribeDanger or DescribeMargin).
std::string FrameHeadline(const TrackedFrame& frame);
} // namespace vp

#endif
