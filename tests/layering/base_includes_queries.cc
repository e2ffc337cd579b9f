// Must not build (tests/layering/CMakeLists.txt): base/ is the bottom
// subject, and a base source that includes a queries header fails.
#include "queries/bezier_net.h"
