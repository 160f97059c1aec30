#include "vpDwellPoints.h"

#include "vpInputError.h"
#include "vpNumericCsv.h"
#include "vpRegularFile.h"

#include <cmath>
#include <cstdint>
#include <fstream>

namespace vp
{
namespace
{
double Distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

std::array<double, 3> Apply(const std::array<double, 16>& m, const std::array<double, 16>& tip)
{
  std::array<double, 3> p{};
  for (int a = 0; a < 3; ++a)
  {
    p[a] = m[4 * a] * tip[3] + m[4 * a + 1] * tip[7] + m[4 * a + 2] * tip[11] + m[4 * a + 3];
  }
  return p;
}

/// The longest run from first whose tips stay within radius of their mean: its end (exclusive).
std::size_t StillRun(const std::vector<std::array<double, 3>>& tips, std::size_t first, double radiusMm, std::array<double, 3>& mean)
{
  mean = tips[first];
  std::size_t end = first + 1;
  for (; end < tips.size(); ++end)
  {
    const double n = static_cast<double>(end - first + 1);
    std::array<double, 3> next{};
    for (int a = 0; a < 3; ++a)
    {
      next[a] = (mean[a] * (n - 1.0) + tips[end][a]) / n;
    }
    bool still = true;
    for (std::size_t k = first; k <= end && still; ++k)
    {
      still = Distance(tips[k], next) <= radiusMm;
    }
    if (!still)
    {
      break;
    }
    mean = next;
  }
  return end;
}
} // namespace

std::vector<DwellPoint> FindDwellPoints(const std::vector<double>& timesS, const std::vector<std::array<double, 16>>& toolPoses,
  const std::array<double, 16>& tipToTool, const DwellSettings& settings)
{
  std::vector<std::array<double, 3>> tips, origins;
  for (const auto& m : toolPoses)
  {
    tips.push_back(Apply(m, tipToTool));
    origins.push_back({ m[3], m[7], m[11] });
  }
  std::vector<DwellPoint> dwells;
  for (std::size_t first = 0; first < tips.size();)
  {
    std::array<double, 3> mean{};
    const std::size_t end = StillRun(tips, first, settings.TipRadiusMm, mean);
    if (timesS[end - 1] - timesS[first] < settings.MinimumS)
    {
      ++first;
      continue;
    }
    DwellPoint d;
    d.PointMm = mean;
    d.StartS = timesS[first];
    d.EndS = timesS[end - 1];
    d.Poses = end - first;
    for (std::size_t k = first; k < end; ++k)
    {
      d.TipSpreadMm = std::max(d.TipSpreadMm, Distance(tips[k], mean));
      for (std::size_t j = first; j < k; j += 4) // every fourth pair: the spread, not every pair
      {
        d.ShaftMotionMm = std::max(d.ShaftMotionMm, Distance(origins[k], origins[j]));
      }
    }
    // A run that resumes the last one (a jitter broke it) extends it.
    if (!dwells.empty() && Distance(dwells.back().PointMm, d.PointMm) <= settings.MergeMm)
    {
      DwellPoint& last = dwells.back();
      const double n = static_cast<double>(last.Poses + d.Poses);
      for (int a = 0; a < 3; ++a)
      {
        last.PointMm[a] = (last.PointMm[a] * static_cast<double>(last.Poses) + d.PointMm[a] * static_cast<double>(d.Poses)) / n;
      }
      last.EndS = d.EndS;
      last.Poses += d.Poses;
      last.TipSpreadMm = std::max(last.TipSpreadMm, d.TipSpreadMm);
      last.ShaftMotionMm = std::max(last.ShaftMotionMm, d.ShaftMotionMm);
    }
    else
    {
      dwells.push_back(d);
    }
    first = end;
  }
  std::vector<DwellPoint> landmarks;
  for (const DwellPoint& d : dwells)
  {
    if (d.ShaftMotionMm >= settings.ShaftMotionMm)
    {
      landmarks.push_back(d);
    }
  }
  return landmarks;
}

std::array<double, 16> ReadMatrixText(const std::string& fileName)
{
  const std::uint64_t size =
    RegularFileSize(fileName, "is a folder, not a transform", "is not a regular file (a device, pipe or socket), not a transform");
  if (size > 65536)
  {
    throw InputError(fileName, "is " + std::to_string(size) + " bytes: not a 4x4 transform (16 numbers)");
  }
  std::ifstream in(fileName);
  std::string text, line;
  while (std::getline(in, line))
  {
    text += line.substr(0, line.find('#')) + " ";
  }
  std::vector<double> values;
  std::string problem;
  if (!ParseSeparatedNumbers(text, values, problem) || values.size() != 16)
  {
    throw InputError(fileName, "expected a 4x4 transform: 16 numbers, row-major" +
        (problem.empty() ? ", got " + std::to_string(values.size()) : " (" + problem + ")"));
  }
  std::array<double, 16> m{};
  std::copy(values.begin(), values.end(), m.begin());
  return m;
}
} // namespace vp
