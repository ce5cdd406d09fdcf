# The two commands of the README:
#   make reproduce   set up (.venv, FMU build) and reproduce the paper into results/
#   make test        set up and run every test (CTest, sanitizers, pytest): what CI runs
# and the fast tier for every change:
#   make check       set up and run the law, the FMUs, the rig and the CLI's core
#                    (ruff check, release C tests, pytest -m "not slow"): under 2 minutes
.PHONY: setup reproduce test check bench fmus crosscheck docs generated clean

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

# Regenerates the cross-check files under cross-check/ from the FMUs.
crosscheck: setup
	.venv/bin/python tools/make_crosscheck.py

# Regenerates docs/reference/variables.md (from the variable tables, through the
# installed package's manifests and FMUs: hence setup, which rebuilds what changed)
# and docs/reference/cli.md (from the parser); tests/contracts/test_reference_docs.py
# fails while either differs from what this writes.  Also the contact patch's
# and pad's guides' figures (tools/make_patch_figures.py, from the bundled scenarios)
# and the experiment design's (tools/make_design_figure.py).
docs: setup
	.venv/bin/python tools/make_reference.py
	.venv/bin/python tools/make_patch_figures.py
	.venv/bin/python tools/make_design_figure.py

# Regenerates python/orthocontact/fmu/generated.py (ContactParams, the law's and
# the patch's rows) from the variable tables, through the installed manifests:
# hence setup.  tests/fmu/test_generated.py fails while it differs from what this writes.
generated: setup
	.venv/bin/python tools/make_generated.py

clean:
	rm -rf build results .venv
