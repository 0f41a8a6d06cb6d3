# sweep.mk - the suite of `modrt sweep` (docs/sweeps.md); included by the Makefile.
#   make test-sweep   metrics against closed forms, the draws, located errors, and one
#                     campaign run locally, under GNU parallel and as a Slurm array job on
#                     a single-node cluster the test starts (tests/sweep/sweep.sh)
test-sweep: deps-sweep build/host/modrt build/host/svgplot
	@sh tests/sweep/sweep.sh build/host
deps-sweep:
	@sh tools/install-deps.sh --auto sweep
TEST_SUITES += test-sweep
.PHONY: test-sweep deps-sweep
