// What this build of the library can do, as configuration keys ask it.
#include "config/build_features.h"

#include "soundpaint/config.h"

namespace sp {

bool embree_available() {
#ifdef SOUNDPAINT_HAVE_EMBREE
  return true;
#else
  return false;
#endif
}

}  // namespace sp
