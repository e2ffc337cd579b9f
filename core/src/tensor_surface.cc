#include "freeform/core/tensor_surface.h"
