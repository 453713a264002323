"""Where `cmake --install` puts the skyspec module for an install prefix (python/CMakeLists.txt).

Usage: python3 site_dir.py PREFIX. Prints the directory the interpreter running it imports from
for that prefix: a virtual environment at PREFIX: its site-packages; Debian's python3 with the
prefix /usr/local: /usr/local/lib/python3.X/dist-packages (on its sys.path, so `import skyspec`
works in any directory); any other prefix: PREFIX/lib/python3.X/site-packages (add it to
PYTHONPATH, or make the prefix a virtual environment).
"""
import os
import sys
import sysconfig

prefix = os.path.abspath(sys.argv[1])
schemes = sysconfig.get_scheme_names()
where = {"base": prefix, "platbase": prefix}
if os.path.exists(os.path.join(prefix, "pyvenv.cfg")):
    scheme = "venv" if "venv" in schemes else "posix_prefix"
elif prefix == "/usr/local" and "posix_local" in schemes:  # Debian: posix_local adds the "local"
    scheme, where = "posix_local", {"base": "/usr", "platbase": "/usr"}
else:
    scheme = "posix_prefix"
print(sysconfig.get_path("platlib", scheme, where))
