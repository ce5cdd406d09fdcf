# The two commands of the README:
#   make reproduce   set up (.venv, FMU build) and reproduce the paper into results/
#   make test        set up and run every test (CTest, sanitizers, pytest): what CI runs
# and the fast tier for every change:
#   make check       set up and run the law, the FMUs, the rig and the CLI's core
#                    (ruff check, release C tests, pytest -m "not slow"): under 2 minutes
.PHONY: setup reproduce test check bench fmus generated clean

setup:
	tools/bootstrap.sh

reproduce: setup
	.venv/bin/orthocontact reproduce --out results

test:
	tools/run_tests.sh

check:
	tools/run_tests.sh --fast

bench: setup
	tools/bench.sh

# Both models' FMUs (FMI 2.0 and 3.0, binaries for every desktop platform)
# into dist/, without the Python analysis stack (tools/build_fmus.sh).
fmus:
	tools/build_fmus.sh

# Every generated file, in one command, from the variable tables, the parser
# and the sources, after the set-up (which rebuilds the FMUs and the manifests
# the build generates from the tables): fmu/generated.py and fmu/tables.json
# (tools/make_generated.py: the one way the tables reach Python), the
# repository's model descriptions (CMake's update_model_description), the
# reference pages (docs/reference/variables.md, cli.md and the generated
# blocks of the others: tools/make_reference.py), the guides' figures
# (tools/make_patch_figures.py, tools/make_design_figure.py) and the FMI
# cross-check files (tools/make_crosscheck.py).  Each test of a generated
# file fails while it differs, naming this command.
generated: setup
	.venv/bin/python tools/make_generated.py
	cmake -S . -B build/ctest-release -DOC_BUILD_TESTS=ON -DCMAKE_BUILD_TYPE=Release \
	  -DFMI_HEADERS_DIR="$$(.venv/bin/python -c 'import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), "c-code"))')" >/dev/null
	cmake --build build/ctest-release --target update_model_description >/dev/null
	.venv/bin/python tools/make_reference.py
	.venv/bin/python tools/make_patch_figures.py
	.venv/bin/python tools/make_design_figure.py
	.venv/bin/python tools/make_crosscheck.py

clean:
	rm -rf build results .venv
