#ifndef vtkVesselModelsRepresentation_h
#define vtkVesselModelsRepresentation_h

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkActor;
class vtkPolyData;
class vtkRenderer;

/// One actor per vessel class, coloured by the label table (Resources/VesselLabels.json unless
/// SetClassColour() says otherwise). The surfaces are shown as given; nothing here changes when
/// the scalpel moves. The liver, when added, is drawn translucent so the vessels inside show; the
/// tumours (SetTumour) in vp::TumourDisplayColour, half translucent so that a tip inside one shows.
class vtkVesselModelsRepresentation : public vtkObject
{
public:
  static vtkVesselModelsRepresentation* New();
  vtkTypeMacro(vtkVesselModelsRepresentation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Adds (or replaces) the surface of a class; its colour comes from the label table.
  void SetVessel(const std::string& className, vtkPolyData* surface);
  /// Adds (or replaces) a tumour's surface, under its id.
  void SetTumour(const std::string& id, vtkPolyData* surface);
  vtkActor* GetTumourActor(const std::string& id) const;
  int GetNumberOfTumours() const { return static_cast<int>(this->Tumours.size()); }
  /// Opacity of the tumours (default 0.5).
  vtkSetClampMacro(TumourOpacity, double, 0.0, 1.0);
  vtkGetMacro(TumourOpacity, double);
  /// RGB 0..1; overrides the label table for this class.
  void SetClassColour(const std::string& className, const std::array<double, 3>& rgb);
  std::array<double, 3> GetClassColour(const std::string& className) const;
  /// Opacity of the liver parenchyma (default 0.15); vessels are opaque.
  vtkSetClampMacro(LiverOpacity, double, 0.0, 1.0);
  vtkGetMacro(LiverOpacity, double);

  /// Vessels seen through: every vessel class drawn at SeeThroughOpacity (default 0.3) instead of
  /// opaque, so that a tip behind them shows. A view from a fixed direction turns it on for a
  /// frame whose tip a vessel hides (vtkVesselProximityView). Default off.
  void SetSeeThrough(bool seeThrough);
  bool GetSeeThrough() const { return this->SeeThrough; }
  vtkSetClampMacro(SeeThroughOpacity, double, 0.0, 1.0);
  vtkGetMacro(SeeThroughOpacity, double);

  void AddToRenderer(vtkRenderer* renderer);
  void RemoveFromRenderer(vtkRenderer* renderer);
  vtkActor* GetActor(const std::string& className) const;
  /// The vessel classes' actors, not the liver's nor the tumours'.
  std::vector<vtkActor*> GetVesselActors() const;
  int GetNumberOfClasses() const { return static_cast<int>(this->Entries.size()); }

protected:
  vtkVesselModelsRepresentation();
  ~vtkVesselModelsRepresentation() override;

  struct Entry
  {
    std::string ClassName;
    vtkSmartPointer<vtkActor> Actor;
  };
  std::vector<Entry> Entries;
  std::vector<Entry> Tumours;
  double TumourOpacity = 0.5;
  std::vector<vtkRenderer*> Renderers; // not owned: the renderers own us in spirit
  double LiverOpacity = 0.15;
  bool SeeThrough = false;
  double SeeThroughOpacity = 0.3;

private:
  vtkVesselModelsRepresentation(const vtkVesselModelsRepresentation&) = delete;
  void operator=(const vtkVesselModelsRepresentation&) = delete;
  void Style(Entry& entry, const std::array<double, 3>& rgb) const;
  /// The actor of name among entries, or null.
  static vtkActor* FindActor(const std::vector<Entry>& entries, const std::string& name);
  /// A new actor (with its mapper, in every renderer) for name, at the end of entries.
  Entry& AddEntry(std::vector<Entry>& entries, const std::string& name);
};

#endif
