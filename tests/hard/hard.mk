# hard.mk - the hard-case suite (tests/hard/hard.py, docs/solvers.md): `make test` runs
# it at sizes that fit CI; `make hard` runs the long versions and writes the table into
# build/hard-table.md. Included at the end of the Makefile.
test-hard: deps-host build/host/modrt
	@python3 tests/hard/hard.py build/host/modrt

hard: deps-host build/host/modrt
	@python3 tests/hard/hard.py build/host/modrt --long --table build/hard-table.md

TEST_SUITES += test-hard
.PHONY: test-hard hard
