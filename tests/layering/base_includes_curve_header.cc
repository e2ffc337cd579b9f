// Must not build (tests/layering/CMakeLists.txt): the public curve.h belongs
// to geometry/, above base/.
#include "freeform/core/curve.h"
