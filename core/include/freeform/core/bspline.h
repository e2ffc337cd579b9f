// Placeholder: being written.
#ifndef FREEFORM_CORE_BSPLINE_H_
#define FREEFORM_CORE_BSPLINE_H_
#endif  // FREEFORM_CORE_BSPLINE_H_
