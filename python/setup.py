"""The one build step pyproject.toml cannot say: record, in the installed
package's offbench/_installed.py, the absolute path of the liboffbench.so.0
this install is for.  An installed copy no longer knows where the checkout
is, so without it every call needed OFFBENCH_LIB (offbench/_lib.py reads
the record after $OFFBENCH_LIB and the checkout's build/)."""

import os

from setuptools import setup
from setuptools.command.build_py import build_py

SONAME = "liboffbench.so.0"
HERE = os.path.dirname(os.path.abspath(__file__))


def library():
    """$OFFBENCH_LIB as set at install time, else the checkout's
    build/liboffbench.so.0 when `make lib` has made it, else None (nothing
    to record: the package then looks where docs/python.md says)."""
    env = os.environ.get("OFFBENCH_LIB")
    if env:
        return os.path.abspath(env)
    built = os.path.join(os.path.dirname(HERE), "build", SONAME)
    return built if os.path.exists(built) else None


class BuildPy(build_py):
    """build_py, then offbench/_installed.py beside the copied modules (in
    the build directory only: the source tree is left as it is).  Not for
    an editable install, which imports the checkout and finds build/ itself."""

    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        target = os.path.join(self.build_lib, "offbench", "_installed.py")
        with open(target, "w") as f:
            f.write('"""Written by setup.py at install time: the library this install is for."""\n')
            f.write("LIBRARY = %r\n" % (library(),))


setup(cmdclass={"build_py": BuildPy})
