// Placeholder: being written.
#ifndef FREEFORM_CORE_NORMALS_H_
#define FREEFORM_CORE_NORMALS_H_
#endif  // FREEFORM_CORE_NORMALS_H_
