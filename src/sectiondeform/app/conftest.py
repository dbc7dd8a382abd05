"""Skip this folder's doctests when the extra ``[app]`` is not installed (core-only test runs)."""

import importlib.util

collect_ignore_glob = [] if all(importlib.util.find_spec(m) for m in ("starlette", "uvicorn")) else ["*.py"]
