"""The ``ballpass`` command: one entry point, one subcommand per job.

Each subcommand lives in :mod:`ballpass.commands` as a module with
``add_parser(subparsers)``; that function builds the sub-parser and sets
``func=run``. Heavy imports happen inside ``run`` so ``ballpass --help`` is instant.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings

#: subcommand name -> module under ballpass.commands
SUBCOMMANDS = {
    "simulate": "simulate",
    "models": "models",
    "bearings": "bearings",
    "features": "features",
    "plot": "plot",
    "diagnose": "diagnose",
    "generate": "generate",
    "examples": "examples",
    "info": "info",
    "benchmark": "benchmark",
    "twin": "twin",
    "work-precision": "work_precision",
    "bifurcation": "bifurcation",
}


class _Parser(argparse.ArgumentParser):
    """argparse's parser (its sub-parsers are of the same class), but a usage error is
    one line, as every other bad input: what is wrong and where the options are listed,
    without argparse's usage block before it."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message} (`{self.prog} --help` lists the "
                     "options)\n")


def build_parser() -> argparse.ArgumentParser:
    """Return the top-level parser with every available subcommand."""
    from . import __version__

    parser = _Parser(
        prog="ballpass",
        description="Rolling-element-bearing vibration: simulate, analyse, diagnose, generate.",
    )
    parser.add_argument("--version", action="version", version=f"ballpass {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for module_name in SUBCOMMANDS.values():
        try:
            module = importlib.import_module(f".commands.{module_name}", __package__)
        except ModuleNotFoundError as exc:
            if exc.name == f"{__package__}.commands.{module_name}":
                continue  # subcommand not installed in this build
            raise
        module.add_parser(sub)
    parser.commands = sub.choices  # name -> its parser, to name its options in errors
    return parser


def _one_line(message, category, filename, lineno, line=None) -> str:
    """Warnings as one line on stderr, without the source line that raised them."""
    return f"ballpass: warning: {message}\n"


#: exit code of a command stopped by Ctrl-C or SIGTERM (128 + SIGINT, as shells report)
EXIT_INTERRUPTED = 130
#: exit code when the reader of the output went away (128 + SIGPIPE, as ``cat`` gives)
EXIT_BROKEN_PIPE = 141


#: set by :func:`_interrupt`: a library that swallows the KeyboardInterrupt (numpy's
#: comparison of structured arrays turns it into "Cannot compare structured arrays")
#: still ends the command as interrupted, not with its error
_stop_asked = False


def _interrupt(signum, frame) -> None:
    """SIGINT and SIGTERM handler: stop the command as Ctrl-C does (cleanly, workers
    stopped), remembering that a stop was asked."""
    global _stop_asked
    _stop_asked = True
    raise KeyboardInterrupt


def main(argv: list[str] | None = None) -> int:
    """Run the ``ballpass`` command; returns the process exit code.

    Ctrl-C and SIGTERM end any command with one line on stderr and exit code 130
    (``generate`` says how many shards are written); output cut short by its reader
    (``ballpass info DIR | head -1``) ends quietly with exit code 141.
    """
    import signal
    import threading

    global _stop_asked
    _stop_asked = False
    in_main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _interrupt) if in_main else None
    # Ctrl-C as Python's own handler does it, but remembered; left alone when ignored
    # (a background job) or handled by the caller
    ctrl_c = in_main and signal.getsignal(signal.SIGINT) is signal.default_int_handler
    if ctrl_c:
        signal.signal(signal.SIGINT, _interrupt)
    try:
        code = _run(argv)
        sys.stdout.flush()        # a closed pipe shows here, not at interpreter exit
        return code
    except KeyboardInterrupt as exc:
        words = sys.argv[1:] if argv is None else argv
        command = next((w for w in words if w in SUBCOMMANDS), None)
        notes = "".join(f"; {note}" for note in getattr(exc, "__notes__", ()))
        print(f"ballpass{' ' + command if command else ''}: interrupted{notes}",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        _discard_stdout()
        return EXIT_BROKEN_PIPE
    finally:
        if in_main:
            signal.signal(signal.SIGTERM, previous)
        if ctrl_c:
            signal.signal(signal.SIGINT, signal.default_int_handler)


def _discard_stdout() -> None:
    """Point stdout at the null device: its reader is gone, so what is left of the
    output (and Python's flush at exit) goes nowhere instead of raising again."""
    import os

    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):   # not a real file (captured)
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, fd)
    os.close(devnull)


def _run(argv: list[str] | None) -> int:
    """Parse ``argv`` and run the subcommand; bad inputs end in one line, exit code 2."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "func", None) is None:
        parser.print_help()
        return 2
    previous, warnings.formatwarning = warnings.formatwarning, _one_line
    try:
        return int(args.func(args) or 0)
    except BrokenPipeError:
        raise               # not a bad input: the reader of stdout went away
    except (ValueError, TypeError, OSError, RuntimeError, MemoryError) as exc:
        if _stop_asked:  # the interrupt, turned into another error on its way up
            raise KeyboardInterrupt from exc
        message = _message(exc)
        if message is None:
            raise  # a bug, not a bad input: keep the traceback
        message = _as_typed(message, parser.commands[args.command])
        print(f"ballpass {args.command}: error: {message}", file=sys.stderr)
        return 2
    finally:
        warnings.formatwarning = previous


def _as_typed(message: str, command: argparse.ArgumentParser) -> str:
    """A library's refusal of an argument the command passed on (``"band must satisfy
    ..."``), with the option the user typed put first (``"--band: band must ..."``)."""
    import re

    named = re.match(r"(\w+) must ", message)
    for action in command._actions if named else ():
        if action.dest == named[1] and action.option_strings:
            return f"{max(action.option_strings, key=len)}: {message}"
    return message


def _message(exc: BaseException) -> str | None:
    """One line saying what went wrong, or None for an error that is a bug."""
    text = str(exc)
    if isinstance(exc, RuntimeError):
        if "no locator available" in text:  # numba cannot write its kernel cache
            return ("numba cannot cache the compiled simulator kernels: neither the package "
                    "folder nor the user cache folder is writable. Set NUMBA_CACHE_DIR to a "
                    "writable folder, e.g. `export NUMBA_CACHE_DIR=/tmp/numba-cache`")
        from .simulate._shared import SimulationUnstableError

        if not isinstance(exc, SimulationUnstableError):
            return None
    if isinstance(exc, MemoryError):
        text = "out of memory" + (f" ({text})" if text else "") + \
            ": ask for less (shorter duration, lower fs, fewer rows)"
    if isinstance(exc, OSError) and exc.filename is not None and exc.strerror:
        text = f"{exc.filename}: {exc.strerror}"
    lines = text.strip().splitlines() or [type(exc).__name__]
    return lines[0] if len(lines) == 1 else f"{lines[0]} (...)"


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
