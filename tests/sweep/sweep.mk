# sweep.mk - the suite of `modrt sweep` (docs/sweeps.md); included by the Makefile.
#   make test-sweep   metrics against closed forms, the draws, located errors, and one
#                     campaign run locally, under GNU parallel and as a Slurm array job on
#                     a single-node cluster the test starts (tests/sweep/sweep.sh)
#   make sweep-bench  what each engine costs per run (tools/dev/bench/sweep_bench.sh)
#   make sweep-figures  the example campaigns of docs/sweeps.md and their figures
test-sweep: deps-sweep build/host/modrt build/host/svgplot
	@sh tests/sweep/sweep.sh build/host
deps-sweep:
	@sh tools/install-deps.sh --auto sweep
# the figures of docs/sweeps.md, "What a campaign costs" (wall clock: on an idle machine)
sweep-bench: deps-sweep build/host/modrt build/host/svgplot
	@sh tools/dev/bench/sweep_bench.sh build/host
# the figures of docs/sweeps.md's examples: each campaign run whole, its plots copied
SWEEP_FIG := build/sweep-figures
SWEEP_FIGS := pi_loop_mc:overshoot-hist:overshoot pi_loop_mc:settling-hist:settling \
              pi_loop_mc:settling-vs-set.Plant.T:settling-vs-T \
              pi_loop_mc:overshoot-vs-set.Plant.K:overshoot-vs-K \
              lane_change_mc:margin-hist:margin lane_change_mc:margin-vs-set.V1.Cf:margin-vs-Cf \
              lane_change_mc:margin-vs-set.V1.m:margin-vs-m
sweep-figures: build/host/modrt build/host/svgplot
	@mkdir -p $(SWEEP_FIG) && for c in pi_loop_mc lane_change_mc; do rm -rf $(SWEEP_FIG)/$$c && \
	  build/host/modrt sweep run docs/sweeps/$$c.swp --out $(SWEEP_FIG)/$$c -j $(JOBS) && \
	  build/host/modrt sweep collect $(SWEEP_FIG)/$$c || exit 1; done
	@for f in $(SWEEP_FIGS); do c=$${f%%:*}; r=$${f#*:}; \
	  cp $(SWEEP_FIG)/$$c/plots/$${r%%:*}.svg docs/sweeps/$$c-$${r#*:}.svg || exit 1; done
TEST_SUITES += test-sweep
.PHONY: test-sweep deps-sweep sweep-bench sweep-figures
