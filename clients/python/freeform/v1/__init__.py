"""The messages of freeform.v1 (geometry_pb2, query_pb2, curve_service_pb2,
surface_service_pb2, with *_pb2_grpc stubs and .pyi type hints), generated
by protoc from the repository's proto/freeform/v1/*.proto when the package
is built (setup.py)."""
