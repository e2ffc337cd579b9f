// Must not build (tests/layering/CMakeLists.txt): meshing/ sits above
// queries/.
#include "meshing/mesh_plan.h"
