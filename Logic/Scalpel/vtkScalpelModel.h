#ifndef vtkScalpelModel_h
#define vtkScalpelModel_h

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>

#include <vtkPolyData.h> // GetModel() converts the smart pointer inline

/// A tracked instrument: its surface, its tip and axis in model coordinates, and where it is.
///
/// The tip is the point whose distance to the vessels matters; the axis (unit) points from the
/// body out through the tip, the way the tool advances, and gives the directional distance. The
/// defaults follow the PLUS model catalogue, whose instruments have their tip at the origin and
/// their shaft along -z: tip (0, 0, 0), axis (0, 0, 1). ModelToWorld is the tracked pose (after
/// any calibration), row-major, millimetres; it changes every frame and costs nothing to set.
class vtkScalpelModel : public vtkObject
{
public:
  static vtkScalpelModel* New();
  vtkTypeMacro(vtkScalpelModel, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The instrument surface in model coordinates (mm); may be null when only the tip matters.
  void SetModel(vtkPolyData* model);
  vtkPolyData* GetModel() const { return this->Model; }

  vtkSetVector3Macro(TipMm, double);
  vtkGetVector3Macro(TipMm, double);
  /// Normalised on set; a zero vector is refused with vp::InputError.
  void SetAxis(double x, double y, double z);
  vtkGetVector3Macro(Axis, double);

  /// Where the tip definition came from, in words, for reports ("Scalpel.json", the given
  /// tip as the front end names it (a command: its flag), or the automatic finder's reasoning).
  void SetTipSource(const std::string& source) { this->TipSource = source; }
  const std::string& GetTipSource() const { return this->TipSource; }

  /// Row-major 4x4. Setting it does not call Modified(): it changes every frame, and nothing
  /// derived from the model depends on it.
  void SetModelToWorld(const std::array<double, 16>& matrix) { this->ModelToWorld = matrix; }
  const std::array<double, 16>& GetModelToWorld() const { return this->ModelToWorld; }

  void GetTipInWorld(double tip[3]) const;
  void GetAxisInWorld(double axis[3]) const;

protected:
  vtkScalpelModel();
  ~vtkScalpelModel() override;

  vtkSmartPointer<vtkPolyData> Model;
  double TipMm[3] = { 0.0, 0.0, 0.0 };
  double Axis[3] = { 0.0, 0.0, 1.0 };
  std::string TipSource = "default (PLUS catalogue: tip at the origin, axis +z)";
  std::array<double, 16> ModelToWorld{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

private:
  vtkScalpelModel(const vtkScalpelModel&) = delete;
  void operator=(const vtkScalpelModel&) = delete;
};

#endif
