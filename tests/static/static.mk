# static.mk - `make test-static`: no circle in the include-and-call graph between the files
# of rt/, tools/scenec and tools/modrt (tests/static/file_graph.py), every file of rt/, tools/scenec
# and tools/modrt in the tables of docs/architecture.md (tests/static/doc_files.py), the
# limits' defaults in rt/rt_limits.h as their list gives them (tests/static/limit_defaults.py),
# applications and API tests reading the runtime through rt.h alone, white-box tests in
# tests/whitebox (tests/static/api_only.py), then cppcheck and clang-tidy on rt/, models/
# and ports/ with zero findings
# (tests/static/static.sh, docs/reliability.md). Included at the end of the Makefile.
test-static: deps
	@python3 tests/static/file_graph.py rt tools/scenec tools/modrt
	@python3 tests/static/doc_files.py docs/architecture.md
	@python3 tests/static/limit_defaults.py
	@python3 tests/static/api_only.py
	@sh tests/static/static.sh

TEST_SUITES += test-static
.PHONY: test-static
