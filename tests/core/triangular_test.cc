#include "freeform/core/triangular.h"
