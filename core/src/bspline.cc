#include "freeform/core/bspline.h"
