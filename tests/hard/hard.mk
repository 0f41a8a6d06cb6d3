# hard.mk - the hard-case suite (tests/hard/hard.py, docs/solvers.md): `make test` runs
# it at sizes that fit CI; `make hard` runs the long versions and writes the table into
# build/hard-table.md. Included at the end of the Makefile.
# test-hard: the suite's two lanes side by side (hard.py --lane), their outputs in turn
test-hard: deps-host build/host/modrt
	@mkdir -p build/hard; python3 tests/hard/hard.py build/host/modrt --lane 2 > build/hard/lane2.out 2>&1 & \
	 p=$$!; python3 tests/hard/hard.py build/host/modrt --lane 1; a=$$?; wait $$p; b=$$?; \
	 cat build/hard/lane2.out; [ $$a -eq 0 ] && [ $$b -eq 0 ]

hard: deps-host build/host/modrt
	@python3 tests/hard/hard.py build/host/modrt --long --table build/hard-table.md

TEST_SUITES += test-hard
.PHONY: test-hard hard
