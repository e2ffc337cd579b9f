// Must not build (tests/layering/CMakeLists.txt): the public subdivision.h
// belongs to refine/, the subject just above kinds/.
#include "freeform/core/subdivision.h"
