// Must not build (tests/layering/CMakeLists.txt): faces/ sits above
// meshing/.
#include "faces/face_boundary.h"
