// Must not build (tests/layering/CMakeLists.txt): faces/ sits above
// triangulation/.
#include "faces/face_boundary.h"
