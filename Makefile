# The two commands of the README:
#   make reproduce   set up (.venv, FMU build) and reproduce the paper into results/
#   make test        set up and run every test (CTest, sanitizers, pytest)
.PHONY: setup reproduce test bench clean

setup:
	tools/bootstrap.sh

reproduce: setup
	.venv/bin/orthocontact reproduce --out results

test:
	tools/run_tests.sh

bench: setup
	tools/bench.sh

clean:
	rm -rf build results .venv
