"""cases_estimates.py - hard cases of the error estimates and the work bound (issue 26,
classes C, F, G): filled below."""


def extra(s, long):
    pass
