#include "vpTrajectoryCheck.h"

#include "vpInputError.h"

#include <algorithm>
#include <cmath>

namespace vp
{
TrajectoryCheck::TrajectoryCheck(const double vesselBounds[6], double rangeMm)
  : RangeMm(rangeMm)
{
  for (int k = 0; k < 6; ++k)
  {
    this->Box[k] = vesselBounds[k] + (k % 2 == 0 ? -rangeMm : rangeMm);
    this->Vessels[k] = vesselBounds[k];
  }
}

bool TrajectoryCheck::InBox(const double box[6], const double tip[3])
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(tip[a] >= box[2 * a] && tip[a] <= box[2 * a + 1]))
    {
      return false;
    }
  }
  return true;
}

void TrajectoryCheck::Add(const TrackedFrame& frame)
{
  const bool inRange = std::any_of(
    frame.Proximity.Classes.begin(), frame.Proximity.Classes.end(), [](const ClassProximity& c) { return c.InRange; });
  this->FramesInRange += inRange ? 1 : 0;
  const double* t = frame.TipMm;
  const double read[3] = { t[0], t[1], t[2] };
  const double metres[3] = { 1000.0 * t[0], 1000.0 * t[1], 1000.0 * t[2] };
  const double micrometres[3] = { 0.001 * t[0], 0.001 * t[1], 0.001 * t[2] };
  const double mirrored[3] = { -t[0], -t[1], t[2] };
  const double* tips[4] = { read, metres, micrometres, mirrored };
  for (std::size_t k = 0; k < 4; ++k)
  {
    this->Near[k] += InBox(this->Box, tips[k]) ? 1 : 0;
    this->Inside[k] += InBox(this->Vessels, tips[k]) ? 1 : 0;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->Extent[2 * a] = std::min(this->Extent[2 * a], t[a]);
    this->Extent[2 * a + 1] = std::max(this->Extent[2 * a + 1], t[a]);
  }
  if (this->Frames > 0 && frame.TimeS - this->PreviousTimeS > 2.0)
  {
    ++this->LongIntervals;
  }
  this->PreviousTimeS = frame.TimeS;
  ++this->Frames;
}

std::vector<TrajectoryWarning> TrajectoryCheck::Warnings() const
{
  std::vector<TrajectoryWarning> warnings;
  if (this->Frames == 0)
  {
    return warnings;
  }
  const std::string frames = std::to_string(this->Frames) + " pose(s)";
  if (this->FramesInRange == 0)
  {
    warnings.push_back({ "no_pose_near_vessels", "none of the " + frames + " came within the " + NumberText(this->RangeMm) +
        " mm range of any vessel: are the poses in the vessels' frame and units?" });
  }
  // A reading is suspected only when the poses as read are nowhere near and most would be: near
  // the vessels' grown box, or, where that holds the origin, inside their own box.
  const auto most = [&](std::size_t n) { return 2 * n > this->Frames; };
  const auto suspect = [&](std::size_t k) {
    return (this->Near[0] == 0 && most(this->Near[k])) || (this->Inside[0] == 0 && most(this->Inside[k]));
  };
  const auto diagonal = [](const double b[6]) {
    return std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  };
  // Metres read as mm where the vessels surround the origin: a trajectory a thousandth of the
  // vessels' size, which times 1000 lies among them.
  const bool tinyInside = this->Frames >= 10 && diagonal(this->Extent) < 1e-3 * diagonal(this->Vessels) &&
    most(this->Inside[1]);
  if (suspect(1) || tinyInside)
  {
    warnings.push_back({ "metres", "the poses lie 1000 times too close to the origin for the vessels; times 1000 they pass " +
        std::string("by them: are they in metres?") });
  }
  if (suspect(2))
  {
    warnings.push_back({ "micrometres", "the poses lie 1000 times too far from the origin for the vessels; divided by 1000 " +
        std::string("they pass by them: are they in micrometres, or the vessels in metres?") });
  }
  if (suspect(3))
  {
    warnings.push_back({ "mirrored", "the poses lie in the mirror image of the vessels (x and y negated): are they in RAS, " +
        std::string("as 3D Slicer writes them?") });
  }
  if (this->Frames >= 3 && 2 * this->LongIntervals >= this->Frames - 1)
  {
    warnings.push_back({ "milliseconds", "most poses are more than 2 s apart, where a tracker sends tens a second: are the " +
        std::string("times in milliseconds?") });
  }
  return warnings;
}
} // namespace vp
