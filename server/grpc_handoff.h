// HandOffToGrpc / TakeBackFromGrpc: the ordering gRPC guarantees between
// our code on different threads, made visible to ThreadSanitizer.
//
// gRPC runs a call's handler, its reactions (OnWriteDone, OnDone) and its
// interceptors on threads of its own, and orders them: OnDone runs after
// Finish, OnWriteDone after StartWrite, every call after the server that
// serves it was built. It does so with synchronization inside libgrpc and
// libabsl_synchronization, which Debian does not build with ThreadSanitizer,
// so under TSan every such hand-off looks like a data race on our objects.
// Call HandOffToGrpc(object) on one side, before the call into gRPC that
// passes control on, and TakeBackFromGrpc(object) first thing where gRPC
// calls us back: under TSan they are a release/acquire pair on `object`'s
// address; otherwise they compile to nothing. They add no ordering that
// gRPC does not already provide, so they cannot hide a real race between
// our threads (docs/testing.md).
#ifndef FREEFORM_SERVER_GRPC_HANDOFF_H_
#define FREEFORM_SERVER_GRPC_HANDOFF_H_

#if defined(__SANITIZE_THREAD__)
#define FREEFORM_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define FREEFORM_TSAN 1
#endif
#endif

#ifdef FREEFORM_TSAN
#include <sanitizer/tsan_interface.h>
#endif

namespace freeform::server {

inline void HandOffToGrpc(const void* object) {
#ifdef FREEFORM_TSAN
  __tsan_release(const_cast<void*>(object));
#else
  (void)object;
#endif
}

inline void TakeBackFromGrpc(const void* object) {
#ifdef FREEFORM_TSAN
  __tsan_acquire(const_cast<void*>(object));
#else
  (void)object;
#endif
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_GRPC_HANDOFF_H_
