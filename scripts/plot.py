#!/usr/bin/python3
"""clearjoint's plotting script: every plot and the HTML report come from here.

    scripts/plot.py <kind> [args...]

Each kind lives in scripts/plotting/<kind>.py and exposes main(argv). When an output cannot be
written (a full disk, an I/O error, a read-only file system) the script exits with 100 + errno
and no traceback: the stage reports the file and the reason on one line (common/plot_script.h). Stages call this script on
their own outputs after writing them (and skip it with --no-plots). Only Debian's
python3-matplotlib is needed; the Agg backend is used so no display is required.
"""
import errno
import importlib
import os
import sys

WRITE_FAILURES = {errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.EROFS, errno.EFBIG}

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def end_with_parent() -> None:
    """Linux: ask for SIGTERM when the stage that started us dies (SIGKILL, the OOM killer), so
    that no plot.py goes on writing into a folder nobody owns. The stage passes its pid as
    CLEARJOINT_PLOT_PARENT; if it is already gone, stop at once. (An MPI rank lives in a process
    group of its own, which run_pipeline's kill of the stage's group does not reach.)"""
    # popped: the variable names *our* parent; a plot.py we start ourselves (the report's
    # field pictures: plot.py fields, under xvfb-run) must not compare its parent with it
    parent = os.environ.pop("CLEARJOINT_PLOT_PARENT", None)
    if not parent or not sys.platform.startswith("linux"):
        return
    try:
        import ctypes
        import signal
        ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGTERM), 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != int(parent):
        sys.exit(143)


def main() -> int:
    end_with_parent()
    kinds = sorted(f[:-3] for f in os.listdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), "plotting"))
                   if f.endswith(".py") and not f.startswith("_"))
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__ + "\nkinds: " + ", ".join(kinds))
        return 0 if len(sys.argv) >= 2 else 1
    kind = sys.argv[1]
    if kind not in kinds:
        print(f"plot.py: unknown kind '{kind}'; allowed: {', '.join(kinds)}", file=sys.stderr)
        return 1
    import matplotlib
    matplotlib.use("Agg")
    module = importlib.import_module(f"plotting.{kind}")
    try:
        return int(module.main(sys.argv[2:]) or 0)
    except OSError as e:
        if e.errno in WRITE_FAILURES:
            return 100 + e.errno
        raise


if __name__ == "__main__":
    sys.exit(main())
