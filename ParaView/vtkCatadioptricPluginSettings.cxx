// Settings the plugin adds when it loads: the images of the compositor, the ray tracer and the
// environment source show in their own colours (Map Scalars off) in a render view. They name the
// plugin's own representation (Representations.xml), so other images keep ParaView's defaults;
// a user's own settings for it come first (a higher priority).
#include "vtkSMSettings.h"

namespace
{
struct RegisterCatadioptricSettings
{
  RegisterCatadioptricSettings()
  {
    vtkSMSettings::GetInstance()->AddCollectionFromString(
      R"({ "representations": { "CatadioptricImageRepresentation": { "MapScalars": 0 } } })", 0.5);
  }
};
const RegisterCatadioptricSettings registerCatadioptricSettings;
}
