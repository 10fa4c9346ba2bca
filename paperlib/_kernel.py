"""The Jupyter kernel that :mod:`paperlib.reproduce` runs notebooks on: ipykernel, minus two false alarms.

``python -m paperlib._kernel -f CONNECTION_FILE`` starts ipykernel's ``IPKernelApp`` exactly as
``python -m ipykernel_launcher`` does, with a logging filter that drops two lines the kernel writes
to the terminal on every successful papermill run:

- ``KeyboardInterrupt caught in kernel``: jupyter_client interrupts the kernel (SIGINT) before
  every shutdown, even an orderly one after the last cell; when the signal lands while the kernel
  handles a message, ipykernel logs it as an error although nothing went wrong;
- ``Kernel is running over TCP without encryption``: papermill's kernels listen on 127.0.0.1 only.

Every other kernel log line (real errors included) still reaches the terminal, and a cell's error
still fails the notebook through papermill.
"""

from __future__ import annotations

import logging
import sys

#: Beginnings of the kernel log messages dropped on a papermill run.
FALSE_ALARMS = ("KeyboardInterrupt caught in kernel", "Kernel is running over TCP without encryption")


class FalseAlarmFilter(logging.Filter):
    """Drop the log records that begin with one of :data:`FALSE_ALARMS`."""

    def filter(self, record: logging.LogRecord) -> bool:
        try:
            message = record.getMessage()
        except Exception:  # a malformed record is not ours to judge
            return True
        return not message.startswith(FALSE_ALARMS)


def main(argv=None) -> None:
    """Start the kernel with :class:`FalseAlarmFilter` on its log (``argv`` as ipykernel_launcher's)."""
    from ipykernel.kernelapp import IPKernelApp

    app = IPKernelApp.instance()
    quiet = FalseAlarmFilter()
    app.log.addFilter(quiet)
    app.initialize(sys.argv[1:] if argv is None else argv)
    if quiet not in app.log.filters:  # the logging configuration may have made a new logger
        app.log.addFilter(quiet)
    app.start()


if __name__ == "__main__":
    # like ipykernel_launcher: take the working folder off sys.path while ipykernel loads (its
    # InteractiveShellApp.init_path puts it back for the notebook's own imports)
    from pathlib import Path

    if sys.path and (sys.path[0] == "" or Path(sys.path[0]) == Path.cwd()):
        del sys.path[0]
    main()
