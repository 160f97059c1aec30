#include "vtkScalpelModel.h"

#include "vpInputError.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <cmath>

vtkStandardNewMacro(vtkScalpelModel);

vtkScalpelModel::vtkScalpelModel() = default;
vtkScalpelModel::~vtkScalpelModel() = default;

void vtkScalpelModel::SetModel(vtkPolyData* model)
{
  if (this->Model != model)
  {
    this->Model = model;
    this->Modified();
  }
}

void vtkScalpelModel::SetAxis(double x, double y, double z)
{
  const double n = std::sqrt(x * x + y * y + z * z);
  if (!(n > 0) || !std::isfinite(n))
  {
    throw vp::InputError("scalpel axis", "must be a non-zero finite vector");
  }
  if (x / n != this->Axis[0] || y / n != this->Axis[1] || z / n != this->Axis[2])
  {
    this->Axis[0] = x / n;
    this->Axis[1] = y / n;
    this->Axis[2] = z / n;
    this->Modified();
  }
}

void vtkScalpelModel::GetTipInWorld(double tip[3]) const
{
  const auto& m = this->ModelToWorld;
  for (int r = 0; r < 3; ++r)
  {
    tip[r] = m[4 * r] * this->TipMm[0] + m[4 * r + 1] * this->TipMm[1] + m[4 * r + 2] * this->TipMm[2] + m[4 * r + 3];
  }
}

void vtkScalpelModel::GetAxisInWorld(double axis[3]) const
{
  const auto& m = this->ModelToWorld;
  for (int r = 0; r < 3; ++r)
  {
    axis[r] = m[4 * r] * this->Axis[0] + m[4 * r + 1] * this->Axis[1] + m[4 * r + 2] * this->Axis[2];
  }
}

void vtkScalpelModel::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << (this->Model ? this->Model->GetNumberOfCells() : 0) << " cells\n";
  os << indent << "TipMm: (" << this->TipMm[0] << ", " << this->TipMm[1] << ", " << this->TipMm[2] << ")\n";
  os << indent << "Axis: (" << this->Axis[0] << ", " << this->Axis[1] << ", " << this->Axis[2] << ")\n";
  os << indent << "TipSource: " << this->TipSource << "\n";
}
