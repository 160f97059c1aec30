#ifndef vpModelRole_h
#define vpModelRole_h

#include <string>

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

/// The role a name says ("vessel", "liver", "tumour"); false, with role unchanged, for any other.
inline bool ModelRoleFromName(const std::string& name, ModelRole& role)
{
  for (ModelRole r : { ModelRole::Vessel, ModelRole::Liver, ModelRole::Tumour })
  {
    if (name == ModelRoleName(r))
    {
      role = r;
      return true;
    }
  }
  return false;
}
} // namespace vp

#endif
