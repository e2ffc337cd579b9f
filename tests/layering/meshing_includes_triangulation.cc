// Must not build (tests/layering/CMakeLists.txt): triangulation/ sits above
// meshing/.
#include "triangulation/predicates.h"
