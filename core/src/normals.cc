#include "freeform/core/normals.h"
