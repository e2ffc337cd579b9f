// Placeholder: being written.
#ifndef FREEFORM_CORE_ELEVATION_H_
#define FREEFORM_CORE_ELEVATION_H_
#endif  // FREEFORM_CORE_ELEVATION_H_
