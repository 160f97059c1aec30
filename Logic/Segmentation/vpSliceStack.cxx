#include "vpSliceStack.h"

#include "vpInputError.h"
#include "vpLabelStructure.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vp
{
namespace
{
using Vector = std::array<double, 3>;

double Dot(const Vector& a, const Vector& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Positions read from text (DS, often 6 significant digits) agree only to about this much.
constexpr double PositionToleranceMm = 1e-3;

bool IsWholeMultiple(double gap, double spacing)
{
  const double ratio = gap / spacing;
  return std::round(ratio) >= 1.0 && std::abs(gap - std::round(ratio) * spacing) <= std::max(0.01, 0.01 * spacing);
}

// The series rule: one spacing (the median gap) everywhere; a gap of several spacings is named as
// missing slices, anything else as uneven spacing.
double ContiguousSpacing(const std::string& where, const std::vector<PlanePlacement>& planes,
  const std::vector<std::size_t>& order, const std::vector<double>& along)
{
  std::vector<double> gaps;
  for (std::size_t i = 1; i < order.size(); ++i)
  {
    gaps.push_back(along[order[i]] - along[order[i - 1]]);
    if (gaps.back() < PositionToleranceMm)
    {
      throw InputError(where, "two slices at the same position (" + planes[order[i - 1]].Name + " and " +
          planes[order[i]].Name + ")");
    }
  }
  if (gaps.empty())
  {
    return 1.0;
  }
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double spacing = sorted[sorted.size() / 2];
  for (std::size_t i = 0; i < gaps.size(); ++i)
  {
    if (std::abs(gaps[i] - spacing) <= std::max(0.01, 0.01 * spacing))
    {
      continue;
    }
    const double ratio = gaps[i] / spacing;
    const std::string between = " between " + planes[order[i]].Name + " and " + planes[order[i + 1]].Name + " (" +
      NumberText(gaps[i]) + " mm where the spacing is " + NumberText(spacing) + " mm)";
    if (ratio > 1.5 && std::abs(ratio - std::round(ratio)) < 0.05)
    {
      throw InputError(where, "missing slice" + std::string(std::round(ratio) > 2.0 ? "s" : "") + between);
    }
    throw InputError(where, "uneven slice spacing" + between);
  }
  return spacing;
}

// The SEG rule: distinct positions on one grid of whole spacings, gaps allowed.
double SparseSpacing(const std::string& where, const std::vector<std::size_t>& order, const std::vector<double>& along, double hint)
{
  std::vector<double> gaps;
  for (std::size_t i = 1; i < order.size(); ++i)
  {
    const double gap = along[order[i]] - along[order[i - 1]];
    if (gap >= PositionToleranceMm)
    {
      gaps.push_back(gap);
    }
  }
  if (gaps.empty())
  {
    return hint > 0.0 ? hint : 1.0;
  }
  const double smallest = *std::min_element(gaps.begin(), gaps.end());
  auto fits = [&](double spacing) {
    return std::all_of(gaps.begin(), gaps.end(), [&](double g) { return IsWholeMultiple(g, spacing); });
  };
  if (hint > 0.0 && fits(hint))
  {
    return hint;
  }
  if (!fits(smallest))
  {
    throw InputError(where, "frames that do not lie on one grid of slices (gaps of " + NumberText(smallest) + " and " +
        NumberText(*std::max_element(gaps.begin(), gaps.end())) + " mm along the normal)");
  }
  return smallest;
}
} // namespace

SliceStack StackPlanes(const std::string& where, const std::vector<PlanePlacement>& planes, StackRule rule,
  double spacingHintMm)
{
  if (planes.empty())
  {
    throw InputError(where, "no image planes");
  }
  const PlanePlacement& first = planes.front();
  const Vector row{ first.Orientation[0], first.Orientation[1], first.Orientation[2] };
  const Vector column{ first.Orientation[3], first.Orientation[4], first.Orientation[5] };
  const Vector normal{ row[1] * column[2] - row[2] * column[1], row[2] * column[0] - row[0] * column[2],
    row[0] * column[1] - row[1] * column[0] };
  if (!(std::abs(std::sqrt(Dot(normal, normal)) - 1.0) <= 1e-3 && std::abs(Dot(row, column)) <= 1e-3))
  {
    throw InputError(where + " (" + first.Name + ")", "ImageOrientationPatient is not two orthogonal unit vectors");
  }
  if (!(first.PixelSpacingMm[0] > 0.0 && first.PixelSpacingMm[1] > 0.0))
  {
    throw InputError(where + " (" + first.Name + ")", "no valid PixelSpacing");
  }
  std::vector<double> along(planes.size());
  for (std::size_t p = 0; p < planes.size(); ++p)
  {
    const PlanePlacement& s = planes[p];
    for (int k = 0; k < 6; ++k)
    {
      if (!(std::abs(s.Orientation[k] - first.Orientation[k]) <= 1e-4))
      {
        throw InputError(where, "slices with different orientations (" + first.Name + " and " + s.Name + ")");
      }
    }
    for (int k = 0; k < 2; ++k)
    {
      if (!(std::abs(s.PixelSpacingMm[k] - first.PixelSpacingMm[k]) <= 1e-4 * first.PixelSpacingMm[k]))
      {
        throw InputError(where, "slices with different pixel spacings (" + first.Name + " and " + s.Name + ")");
      }
    }
    const Vector d{ s.PositionLps[0] - first.PositionLps[0], s.PositionLps[1] - first.PositionLps[1],
      s.PositionLps[2] - first.PositionLps[2] };
    along[p] = Dot(d, normal);
    const double across = std::sqrt(std::max(0.0, Dot(d, d) - along[p] * along[p]));
    if (!(across <= 0.01))
    {
      throw InputError(where, "slices are not stacked along their normal (" + s.Name + " is offset by " +
          NumberText(across) + " mm sideways): a tilted-gantry series, which this reader does not resample");
    }
  }
  std::vector<std::size_t> order(planes.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return along[a] < along[b]; });

  const double spacing = rule == StackRule::Contiguous ? ContiguousSpacing(where, planes, order, along)
                                                       : SparseSpacing(where, order, along, spacingHintMm);
  SliceStack stack;
  const double start = along[order.front()];
  stack.SliceOfPlane.resize(planes.size());
  for (std::size_t p = 0; p < planes.size(); ++p)
  {
    const double k = std::round((along[p] - start) / spacing);
    if (!(k < 1e6))
    {
      throw InputError(where, "frames span more than a million slices");
    }
    stack.SliceOfPlane[p] = static_cast<int>(k);
    stack.NumberOfSlices = std::max(stack.NumberOfSlices, stack.SliceOfPlane[p] + 1);
  }
  const PlanePlacement& lowest = planes[order.front()];
  // Index (i column, j row, k slice) to LPS: i steps along the row direction by the column
  // spacing (PixelSpacing[1]), j along the column direction by the row spacing (PixelSpacing[0]).
  for (int r = 0; r < 3; ++r)
  {
    stack.IjkToLps[4 * r + 0] = row[r] * first.PixelSpacingMm[1];
    stack.IjkToLps[4 * r + 1] = column[r] * first.PixelSpacingMm[0];
    stack.IjkToLps[4 * r + 2] = normal[r] * spacing;
    stack.IjkToLps[4 * r + 3] = lowest.PositionLps[r];
  }
  stack.IjkToLps[15] = 1.0;
  CheckVoxelGeometry(stack.IjkToLps, where);
  return stack;
}
} // namespace vp
