# The two commands of the README:
#   make reproduce   set up (.venv, FMU build) and reproduce the paper into results/
#   make test        set up and run every test (CTest, sanitizers, pytest)
.PHONY: setup reproduce test bench fmus crosscheck clean

setup:
	tools/bootstrap.sh

reproduce: setup
	.venv/bin/orthocontact reproduce --out results

test:
	tools/run_tests.sh

bench: setup
	tools/bench.sh

# Both FMUs (FMI 2.0 and 3.0, binaries for every desktop platform) into dist/.
fmus: setup
	cmake --build build/wheel-* --target dist

# Regenerates the cross-check files under cross-check/ from the FMUs.
crosscheck: setup
	.venv/bin/python tools/make_crosscheck.py

clean:
	rm -rf build results .venv
