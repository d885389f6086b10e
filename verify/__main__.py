"""``python -m verify``: the command line (verify/cli/), quiet on Ctrl-C even while importing."""
import sys

if __name__ == "__main__":
    try:
        from .cli import main
    except KeyboardInterrupt:  # Ctrl-C while sympy, heyoka, ... load
        print("error: interrupted (Ctrl-C)", file=sys.stderr)
        sys.exit(130)
    sys.exit(main())
