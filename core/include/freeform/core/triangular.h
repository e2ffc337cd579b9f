// Placeholder: being written.
#ifndef FREEFORM_CORE_TRIANGULAR_H_
#define FREEFORM_CORE_TRIANGULAR_H_
#endif  // FREEFORM_CORE_TRIANGULAR_H_
