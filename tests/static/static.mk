# static.mk - `make test-static`: cppcheck and clang-tidy on rt/, models/ and ports/ with
# zero findings (tests/static/static.sh, docs/reliability.md). Included at the end of the
# Makefile.
test-static: deps
	@sh tests/static/static.sh

TEST_SUITES += test-static
.PHONY: test-static
