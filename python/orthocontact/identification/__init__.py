"""Parameter identification with casadi, split by job: the data and their
files (measurements), the strip in the fit's model (strip_model), the
paper's formulas and the joint fit (estimators), statistics (statistics),
the job (job) and its figure and Markdown (report)."""
