# The two commands: `make run` and `make test`. Everything else is for developers.
SHELL := /bin/bash
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: run test test-deps test-fast bench lint soak system-deps bytecode clean jazzy-oracle

# The interfaces hook is copied beside its .pth at install time (pyproject's force-include): reinstall on a change.
$(STAMP): pyproject.toml diffctl/interfaces/hook.py
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	@touch $@

# Bytecode for diffctl's own modules (the editable install leaves none, and where PYTHONDONTWRITEBYTECODE is set
# no run ever writes it): every component would compile its imports from source at each start, 0.3 s of the
# fork server's start-up alone. compileall skips what is up to date, so this is cheap when nothing changed.
bytecode: $(STAMP)
	@$(BIN)/python -m compileall -q -j 0 diffctl bench >/dev/null

# Chromium (browser tests), Xvfb (the --gui screenshot test), openssl and iproute2 (the security tests'
# certificates and network-namespace hosts) and cmake (the oracle of the workspace's install-rule index) come
# from Debian's packages. Idempotent: nothing is installed when all are already there.
system-deps:
	@if ! command -v chromium >/dev/null || ! command -v Xvfb >/dev/null || ! command -v openssl >/dev/null \
	    || ! command -v ip >/dev/null || ! command -v cmake >/dev/null; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing chromium, xvfb, openssl, iproute2 and cmake from Debian packages"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium xvfb openssl \
	      iproute2 cmake >/dev/null; \
	  else \
	    echo "chromium/xvfb/openssl/iproute2/cmake missing and cannot apt-get install them: their tests will say so"; \
	  fi; \
	fi

# The oracle of the client library's differential tests: ROS 2 Jazzy's real rclpy with Fast DDS and message
# packages (cp311 wheels from PyPI) in a venv of their own, never in the project's venv, where they would
# stand in for a sourced ROS. Idempotent; a failure is an error.
JAZZY := .venv-jazzy
JAZZY_REQS := tests/oracle/jazzy-requirements.txt

$(JAZZY)/.installed: $(JAZZY_REQS)
	@test -x $(JAZZY)/bin/python || $(PYTHON) -m venv $(JAZZY)
	@$(JAZZY)/bin/python -c 'import sys; assert sys.version_info[:2] == (3, 11), "the ros-jazzy wheels are cp311: make $(JAZZY) with PYTHON=python3.11"'
	$(JAZZY)/bin/python -m pip install -q -r $(JAZZY_REQS)
	@touch $@

jazzy-oracle: $(JAZZY)/.installed

run: $(STAMP) bytecode
	$(BIN)/diffctl launch sim_control

# Both cores (pytest-xdist): most tests wait on child processes, sim time and the bus, so one worker leaves a
# core idle. A test that cannot share the machine goes in an xdist_group (run one after another on one worker).
PYTEST_WORKERS ?= 2
PYTEST_PARALLEL := -n $(PYTEST_WORKERS) --dist loadgroup

# What `make test` needs, made side by side: the two venvs' installs and the Debian packages wait mostly on the
# network and on unpacking, not on one another.
test-deps:
	@$(MAKE) --no-print-directory -j 3 $(STAMP) $(JAZZY)/.installed system-deps

test: test-deps bytecode
	$(BIN)/python -m pytest -p no:cacheprovider $(PYTEST_PARALLEL) --durations=25

test-fast: $(STAMP) bytecode
	$(BIN)/python -m pytest -p no:cacheprovider $(PYTEST_PARALLEL) -m "not slow and not browser"

# `make bench REFERENCE=1` also writes bench/results/reference-<date>-<commit>.json (the file the README cites).
bench: $(STAMP) bytecode jazzy-oracle
	$(BIN)/python -m bench $(if $(REFERENCE),--reference)

lint: $(STAMP)
	$(BIN)/ruff check diffctl tests bench

soak: $(STAMP) bytecode
	$(BIN)/python -m bench.soak

clean:
	rm -rf $(VENV) $(JAZZY) dist build *.egg-info
