# sweep.mk - the suite of `modrt sweep` (docs/sweeps.md); included by the Makefile.
#   make test-sweep   metrics against closed forms, the draws, located errors, and one
#                     campaign run locally, under GNU parallel and as a Slurm array job on
#                     a single-node cluster the test starts (tests/sweep/sweep.sh)
#   make sweep-bench  what each engine costs per run (tools/dev/bench/sweep_bench.sh)
test-sweep: deps-sweep build/host/modrt build/host/svgplot
	@sh tests/sweep/sweep.sh build/host
deps-sweep:
	@sh tools/install-deps.sh --auto sweep
# the figures of docs/sweeps.md, "What a campaign costs" (wall clock: on an idle machine)
sweep-bench: deps-sweep build/host/modrt build/host/svgplot
	@sh tools/dev/bench/sweep_bench.sh build/host
TEST_SUITES += test-sweep
.PHONY: test-sweep deps-sweep sweep-bench
