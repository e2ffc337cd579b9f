#include "freeform/core/elevation.h"
