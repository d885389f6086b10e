"""``python -m verify``: the command line (verify/cli/), quiet on Ctrl-C even while importing.

:func:`verify.guard.supervise` comes first, while nothing heavy is imported (``verify/__init__.py``
imports lazily for this): the process the shell started stays a light supervisor and the command
runs in its child, so that Ctrl-C works even while heyoka compiles for minutes.
"""
import sys

if __name__ == "__main__":
    from .guard import supervise, wants_json

    supervise(sys.argv[1:])  # returns in the child, which runs the command; the parent exits as it does
    try:
        from .cli import main
    except KeyboardInterrupt:  # Ctrl-C while sympy, heyoka, ... load
        if wants_json(sys.argv[1:]) and sys.stdout is not None:
            print('{"error": "interrupted (Ctrl-C)", "exit_status": 130}', flush=True)
        print("error: interrupted (Ctrl-C)", file=sys.stderr)
        sys.exit(130)
    sys.exit(main())
