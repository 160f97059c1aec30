#include "vpTrajectoryCheck.h"

#include "vpInputError.h"

#include <algorithm>

namespace vp
{
TrajectoryCheck::TrajectoryCheck(const double vesselBounds[6], double rangeMm)
  : RangeMm(rangeMm)
{
  for (int k = 0; k < 6; ++k)
  {
    this->Box[k] = vesselBounds[k] + (k % 2 == 0 ? -rangeMm : rangeMm);
  }
}

bool TrajectoryCheck::NearVessels(const double tip[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(tip[a] >= this->Box[2 * a] && tip[a] <= this->Box[2 * a + 1]))
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
    this->Near[k] += this->NearVessels(tips[k]) ? 1 : 0;
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
  // A reading is suspected only when the poses as read are nowhere near and most would be.
  const bool farAsRead = this->Near[0] == 0;
  const auto most = [&](std::size_t n) { return 2 * n > this->Frames; };
  if (farAsRead && most(this->Near[1]))
  {
    warnings.push_back({ "metres", "the poses lie 1000 times too close to the origin for the vessels; times 1000 they pass " +
        std::string("by them: are they in metres?") });
  }
  if (farAsRead && most(this->Near[2]))
  {
    warnings.push_back({ "micrometres", "the poses lie 1000 times too far from the origin for the vessels; divided by 1000 " +
        std::string("they pass by them: are they in micrometres, or the vessels in metres?") });
  }
  if (farAsRead && most(this->Near[3]))
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
