#include "freeform/core/interpolation.h"
