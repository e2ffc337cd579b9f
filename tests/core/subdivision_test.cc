#include "freeform/core/subdivision.h"
