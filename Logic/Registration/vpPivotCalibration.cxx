#include "vpPivotCalibration.h"

#include "vpInputError.h"

#include <vtkMath.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace vp
{
PivotCalibration CalibratePivot(const std::vector<std::array<double, 16>>& poses, std::size_t minimumPoses,
  double minimumRotationDeg)
{
  if (poses.size() < minimumPoses)
  {
    throw InputError("pivot poses", "too few poses: " + std::to_string(poses.size()) + ", at least " +
        std::to_string(minimumPoses) + " are needed");
  }
  PivotCalibration result;
  for (const auto& pose : poses)
  {
    result.RotationSpreadDeg = std::max(result.RotationSpreadDeg, RotationBetweenDeg(poses.front(), pose));
  }
  if (result.RotationSpreadDeg < minimumRotationDeg)
  {
    throw InputError("pivot poses", "too little rotation: the tool turns at most " + NumberText(result.RotationSpreadDeg, 3) +
        " degrees; swing it about its tip through at least " + NumberText(minimumRotationDeg, 3));
  }

  // Each pose gives three rows of [R_i  -I] [tip; pivot] = -t_i; solve the normal equations.
  double normal[6][6] = {};
  double rhs[6] = {};
  for (const auto& m : poses)
  {
    for (int r = 0; r < 3; ++r)
    {
      const double row[6] = { m[4 * r], m[4 * r + 1], m[4 * r + 2], r == 0 ? -1.0 : 0.0, r == 1 ? -1.0 : 0.0,
        r == 2 ? -1.0 : 0.0 };
      for (int i = 0; i < 6; ++i)
      {
        for (int j = 0; j < 6; ++j)
        {
          normal[i][j] += row[i] * row[j];
        }
        rhs[i] += row[i] * -m[4 * r + 3];
      }
    }
  }
  // Conditioning: the smallest eigenvalue per pose. It is 0 when every rotation shares one axis.
  double copy[6][6], eigenvalues[6], vectorStorage[6][6];
  double* a[6];
  double* v[6];
  for (int i = 0; i < 6; ++i)
  {
    std::copy(normal[i], normal[i] + 6, copy[i]);
    a[i] = copy[i];
    v[i] = vectorStorage[i];
  }
  vtkMath::JacobiN(a, 6, eigenvalues, v);
  const double smallest = *std::min_element(eigenvalues, eigenvalues + 6) / static_cast<double>(poses.size());
  if (smallest < 1e-4)
  {
    throw InputError("pivot poses", "the tool turns about one axis only, so the tip cannot be placed along it; "
                                    "swing it in two directions");
  }
  double* rows[6];
  for (int i = 0; i < 6; ++i)
  {
    rows[i] = normal[i];
  }
  double x[6];
  std::copy(rhs, rhs + 6, x);
  if (!vtkMath::SolveLinearSystem(rows, x, 6))
  {
    throw InputError("pivot poses", "the poses do not determine a tip (singular system)");
  }
  result.TipInToolMm = { x[0], x[1], x[2] };
  result.PivotInWorldMm = { x[3], x[4], x[5] };
  double sum = 0.0;
  for (const auto& m : poses)
  {
    const Point3 tip = TransformPoint(m, result.TipInToolMm);
    const double dx = tip[0] - x[3], dy = tip[1] - x[4], dz = tip[2] - x[5];
    sum += dx * dx + dy * dy + dz * dz;
    result.PoseErrorsMm.push_back(std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  result.RmseMm = std::sqrt(sum / static_cast<double>(poses.size()));
  return result;
}
} // namespace vp
