"""The `diffctl` command line: a lazy group whose subcommands live with the package they drive."""
