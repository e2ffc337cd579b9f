"""Builds the freeform package: generates freeform.v1 from the .proto files.

The messages and gRPC stubs of freeform.v1 are generated with Debian's
protoc and grpc_python_plugin (protobuf-compiler, protobuf-compiler-grpc)
into the build folder, from the repository's proto/ (two levels up) or, in
an sdist, from the copy of proto/ it carries. The google.rpc error details
become a descriptor set (freeform/_google_rpc.binpb) that freeform._errors
loads into a pool of its own. Everything else is in pyproject.toml.
"""

import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist

HERE = os.path.dirname(os.path.abspath(__file__))
FREEFORM_PROTOS = ["freeform/v1/%s.proto" % name for name in
                   ("geometry", "query", "curve_service", "surface_service")]
GOOGLE_RPC_PROTOS = ["google/rpc/status.proto",
                     "google/rpc/error_details.proto"]


def proto_root():
    """The folder with freeform/v1/*.proto and third_party/google/rpc."""
    for candidate in (os.path.join(HERE, "proto"),
                      os.path.join(HERE, os.pardir, os.pardir, "proto")):
        if os.path.isfile(os.path.join(candidate, FREEFORM_PROTOS[0])):
            return os.path.normpath(candidate)
    raise SystemExit("setup.py: proto/freeform/v1/*.proto not found: build "
                     "from the freeform repository (clients/python) or its "
                     "sdist")


def tool(name, package):
    path = shutil.which(name)
    if path is None:
        raise SystemExit("setup.py: %s not found: install Debian's %s "
                         "(scripts/setup.sh)" % (name, package))
    return path


def generate(out_dir):
    """Writes freeform/v1/*_pb2{,_grpc}.py{,i} and the google.rpc
    descriptor set into ``out_dir``."""
    out_dir = os.path.abspath(out_dir)
    root = proto_root()
    protoc = tool("protoc", "protobuf-compiler")
    plugin = tool("grpc_python_plugin", "protobuf-compiler-grpc")
    subprocess.check_call(
        [protoc, "--proto_path=" + root, "--python_out=" + out_dir,
         "--pyi_out=" + out_dir, "--grpc_python_out=" + out_dir,
         "--plugin=protoc-gen-grpc_python=" + plugin] + FREEFORM_PROTOS,
        cwd=root)
    # google/protobuf/any.proto and duration.proto come from protoc's own
    # include folder.
    subprocess.check_call(
        [protoc, "--proto_path=" + os.path.join(root, "third_party"),
         "--include_imports",
         "--descriptor_set_out=" + os.path.join(out_dir, "freeform",
                                                "_google_rpc.binpb")] +
        GOOGLE_RPC_PROTOS, cwd=os.path.join(root, "third_party"))


class BuildPyWithProtos(build_py):
    """build_py, then the generated modules into the build folder."""

    def run(self):
        super().run()
        if not self.dry_run:
            generate(self.build_lib)


class SdistWithProtos(sdist):
    """An sdist that carries the .proto files it is built from."""

    def make_release_tree(self, base_dir, files):
        super().make_release_tree(base_dir, files)
        root = proto_root()
        for name in FREEFORM_PROTOS + ["third_party/" + name
                                       for name in GOOGLE_RPC_PROTOS]:
            target = os.path.join(base_dir, "proto", name)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(os.path.join(root, name), target)
        shutil.copyfile(os.path.join(root, "third_party", "google", "LICENSE"),
                        os.path.join(base_dir, "proto", "third_party",
                                     "google", "LICENSE"))


setup(cmdclass={"build_py": BuildPyWithProtos, "sdist": SdistWithProtos})
