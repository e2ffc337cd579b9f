// Placeholder: being written.
#ifndef FREEFORM_CORE_LAGRANGE_H_
#define FREEFORM_CORE_LAGRANGE_H_
#endif  // FREEFORM_CORE_LAGRANGE_H_
