#!/usr/bin/python3
"""Builds and installs the Python package (clients/python) the two ways
docs/clients.md gives, then runs its tests against the real freeformd.

    python_package_test.py --freeformd PATH --cli PATH \\
        --source-dir REPOSITORY --work-dir BUILD_SUBDIR

In the work folder: a copy of clients/python and proto/ (so that nothing is
built in the source tree); an sdist and a wheel made from it by Debian's
python3-build without network (`python3 -m build --no-isolation`), whose
contents are checked; a venv over Debian's site-packages (python3-grpcio,
python3-protobuf, python3-numpy) into which pip installs the package from
the copied folder (`pip install --no-build-isolation --no-index`); mypy
over the installed package; then clients/python/tests under that venv's
python against one freeformd on a free port (clients/python/tests/
support.py; the TLS tests start their own).
"""

import argparse
import os
import shutil
import subprocess
import sys
import zipfile

# What the wheel must hold besides the package's own modules.
GENERATED = ["freeform/py.typed", "freeform/_google_rpc.binpb"] + [
    "freeform/v1/%s%s" % (name, suffix)
    for name in ("geometry", "query", "curve_service", "surface_service")
    for suffix in ("_pb2.py", "_pb2.pyi", "_pb2_grpc.py")]


def run(command, **kwargs):
    print("$ " + " ".join(command), flush=True)
    subprocess.run(command, check=True, **kwargs)


def copy_sources(source_dir, work_dir):
    """clients/python and proto/ under work_dir/src, as in the repository."""
    copy = os.path.join(work_dir, "src")
    shutil.rmtree(copy, ignore_errors=True)
    ignore = shutil.ignore_patterns("build", "dist", "*.egg-info",
                                    "__pycache__")
    shutil.copytree(os.path.join(source_dir, "clients", "python"),
                    os.path.join(copy, "clients", "python"), ignore=ignore)
    shutil.copytree(os.path.join(source_dir, "proto"),
                    os.path.join(copy, "proto"), ignore=ignore)
    return os.path.join(copy, "clients", "python")


def check_wheel(dist_dir):
    wheels = [name for name in os.listdir(dist_dir) if name.endswith(".whl")]
    if len(wheels) != 1 or not any(name.endswith(".tar.gz")
                                   for name in os.listdir(dist_dir)):
        raise RuntimeError("expected one wheel and one sdist in %s: %s" %
                           (dist_dir, os.listdir(dist_dir)))
    with zipfile.ZipFile(os.path.join(dist_dir, wheels[0])) as wheel:
        missing = sorted(set(GENERATED) - set(wheel.namelist()))
    if missing:
        raise RuntimeError("the wheel lacks %s" % ", ".join(missing))
    print("the wheel %s holds the generated modules" % wheels[0])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--freeformd", required=True)
    parser.add_argument("--cli", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--work-dir", required=True)
    args = parser.parse_args()
    for name in ("freeformd", "cli", "source_dir", "work_dir"):
        setattr(args, name, os.path.abspath(getattr(args, name)))
    os.makedirs(args.work_dir, exist_ok=True)
    package = copy_sources(args.source_dir, args.work_dir)

    dist = os.path.join(args.work_dir, "dist")
    shutil.rmtree(dist, ignore_errors=True)
    # The sdist, then the wheel built from the sdist alone.
    run([sys.executable, "-m", "build", "--no-isolation", "--outdir", dist,
         package])
    check_wheel(dist)

    venv = os.path.join(args.work_dir, "venv")
    shutil.rmtree(venv, ignore_errors=True)
    run([sys.executable, "-m", "venv", "--system-site-packages", venv])
    python = os.path.join(venv, "bin", "python")
    run([python, "-m", "pip", "install", "--no-build-isolation",
         "--no-index", "--disable-pip-version-check", package])
    installed = subprocess.run(
        [python, "-c", "import freeform; print(freeform.__file__)"],
        check=True, capture_output=True, text=True,
        cwd=args.work_dir).stdout.strip()
    if not installed.startswith(os.path.abspath(venv) + os.sep):
        raise RuntimeError("freeform imports from %s, not the venv" %
                           installed)

    # The type hints (py.typed) hold together, checked by Debian's mypy on
    # the installed package (settings in clients/python/pyproject.toml).
    run([python, "-m", "mypy", "--config-file",
         os.path.join(package, "pyproject.toml"), "--cache-dir",
         os.path.join(args.work_dir, "mypy_cache"), "-p", "freeform"],
        cwd=args.work_dir)

    environment = dict(os.environ, FREEFORMD=args.freeformd,
                       FREEFORM_CLI=args.cli,
                       FREEFORM_SOURCE_DIR=args.source_dir)
    environment.pop("FREEFORM_ADDRESS", None)
    environment.pop("PYTHONPATH", None)
    tests = os.path.join(args.source_dir, "clients", "python", "tests")
    result = subprocess.run(
        [python, "-m", "unittest", "discover", "-v", "-s", tests],
        env=environment, cwd=args.work_dir)
    return result.returncode


if __name__ == "__main__":
    sys.exit(main())
