#ifndef vpModelRole_h
#define vpModelRole_h

namespace vp
{
/// What a model is for: measured against (a vessel class), shown beside them (the liver), or a
/// tumour whose resection margin is kept.
enum class ModelRole
{
  Vessel,
  Liver,
  Tumour,
};

/// "vessel", "liver", "tumour": the label table's and models.json's "role".
inline const char* ModelRoleName(ModelRole role)
{
  switch (role)
  {
    case ModelRole::Liver:
      return "liver";
    case ModelRole::Tumour:
      return "tumour";
    case ModelRole::Vessel:
      break;
  }
  return "vessel";
}
} // namespace vp

#endif
