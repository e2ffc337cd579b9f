#include "freeform/core/lagrange.h"
