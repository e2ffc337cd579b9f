#include "freeform/core/tessellation.h"
