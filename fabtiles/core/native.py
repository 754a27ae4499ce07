"""Importing a compiled module that a Ctrl+C must not interrupt half-way.

manifold3d builds its Python types (its enums among them) by running Python code
while its module initialises; a KeyboardInterrupt raised there escapes as a C++
exception and the process aborts or crashes instead of stopping cleanly. The
signal cannot simply be blocked: numpy's BLAS threads receive it instead and
Python still raises it in the main thread. So the Python handlers of Ctrl+C and
SIGTERM are swapped for one that only remembers the signal, and the signal is
raised again once the module is in place.
"""

from __future__ import annotations

import importlib
import signal
import sys
import threading
from types import ModuleType

_HELD = (signal.SIGINT, signal.SIGTERM)


def import_uninterrupted(name: str) -> ModuleType:
    """Import the module ``name``, with Ctrl+C and SIGTERM held until it is initialised.

    A signal that arrives meanwhile is raised again afterwards, so the program
    stops exactly as it would have, only once the import is complete. Off the main
    thread (where Python runs no signal handler) this is a plain import.

    Parameters
    ----------
    name : str
        The module's dotted name.

    Returns
    -------
    types.ModuleType
        The module, imported once and then taken from ``sys.modules``.

    Examples
    --------
    >>> import_uninterrupted("math").floor(2.5)
    2
    """
    module = sys.modules.get(name)
    if module is not None:
        return module
    if threading.current_thread() is not threading.main_thread():
        return importlib.import_module(name)
    received: list[int] = []

    def remember(signum, frame):
        received.append(signum)

    # A handler installed outside Python (getsignal gives None) cannot be put back: leave it.
    previous = {s: signal.getsignal(s) for s in _HELD}
    held = {s: h for s, h in previous.items() if h is not None}
    for s in held:
        signal.signal(s, remember)
    try:
        return importlib.import_module(name)
    finally:
        for s, handler in held.items():
            signal.signal(s, handler)
        if received:
            signal.raise_signal(received[0])
