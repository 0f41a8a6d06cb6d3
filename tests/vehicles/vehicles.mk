# vehicles.mk - `make test-vehicles`: the vehicle models and the ISO 3888-1 lane change
# against independent answers (tests/vehicles/vehicles.py, docs/vehicles.md). Included at
# the end of the Makefile.
test-vehicles: deps-host build/host/modrt
	@python3 tests/vehicles/vehicles.py build/host/modrt

TEST_SUITES += test-vehicles
.PHONY: test-vehicles
