import atexit
import os
import shutil
import sys
import tempfile

# Compile every kernel afresh (before numba is imported): Numba's on-disk cache checks only the
# compiled function's own file, so a cached bench kernel that inlines fastrest's code can go on
# running fastrest's old code after an edit (seen: jit.e_table timed at 141 instead of ~72 ns/point).
# Set NUMBA_CACHE_DIR yourself to reuse a cache.
if "NUMBA_CACHE_DIR" not in os.environ:
    _cache = tempfile.mkdtemp(prefix="fastrest-bench-")
    os.environ["NUMBA_CACHE_DIR"] = _cache
    atexit.register(shutil.rmtree, _cache, True)

from .run import main  # noqa: E402

sys.exit(main())
