"""`python -m diffctl` runs the command line; the launcher starts components this way."""

from diffctl.cli.main import main

if __name__ == "__main__":
    main()
