// The method an RPC fuzzer calls (rpc_fuzzer.cc): each fuzzer compiles this
// file with its own FREEFORM_FUZZ_METHOD, e.g.
// "/freeform.v1.CurveService/Evaluate" (tests/fuzz/CMakeLists.txt).
extern const char kFuzzMethod[];
const char kFuzzMethod[] = FREEFORM_FUZZ_METHOD;
