"""In CI, a skipped test fails the run unless it was skipped because the shared real scans
are absent: a missing library, a display or a platform feature would otherwise hide a test
behind one line of the summary.

The guard is a pytest plugin (registered by conftest.py for the whole run, benchmarks/
included) that collects every skip, at collection or at run time, and, when $CI is set to
a true value, turns the session's exit status into a failure listing the skips it does not
accept. Accepted: a reason starting with DATA_ABSENT, only while that folder really is
absent; and COMPARE_EXTRA, a comparison with a library CI does not install (pyKVFinder, whose
matplotlib pin conflicts with the window's). A CI machine with ../shared/data runs every
other test.

Under pytest-xdist each worker runs its own guard over the tests it ran and hands its
refusals to the controller (`workeroutput`), whose guard judges the whole run.
"""

from __future__ import annotations

import os

import pytest
from reference import COMPARE_EXTRA, DATA_ABSENT

TRUE = ("1", "true", "yes", "on")
WORKER_KEY = "skip_guard_refused"


def xdist_role(config: pytest.Config) -> str:
    """"worker" in an xdist worker, "controller" in a run that hands tests to workers,
    else "alone"."""
    if hasattr(config, "workerinput"):
        return "worker"
    dist = getattr(config.option, "dist", "no")
    workers = getattr(config.option, "numprocesses", None)
    return "controller" if dist != "no" and workers else "alone"


def in_ci(environ: dict[str, str] | None = None) -> bool:
    """True when $CI says this run is continuous integration (CI=true, as CI services set)."""
    return (environ if environ is not None else os.environ).get("CI", "").lower() in TRUE


def skip_reason(report: pytest.CollectReport | pytest.TestReport) -> str:
    """The reason a skipped report gives (pytest keeps it as (path, line, 'Skipped: why'))."""
    longrepr = report.longrepr
    text = longrepr[2] if isinstance(longrepr, tuple) and len(longrepr) == 3 else str(longrepr)
    return text.removeprefix("Skipped: ")


def accepted(reason: str, data_present: bool) -> bool:
    """True for the skips CI accepts: shared data absent, while it really is; a library of
    the `compare` extra missing."""
    return (reason.startswith(DATA_ABSENT) and not data_present) or reason == COMPARE_EXTRA


class SkipGuard:
    """Collects the skips of a run; in CI, fails the run on those it does not accept."""

    def __init__(self, data_present: bool, enforce: bool, role: str = "alone") -> None:
        """data_present: the shared data folder is there (then no skip is accepted);
        enforce: fail the session on unaccepted skips (in CI), else only collect them;
        role: "alone" (no xdist), "worker" (reports to its controller) or "controller"
        (judges what its workers report, and only that: it sees no item of its own)."""
        self.data_present = data_present
        self.enforce = enforce
        self.role = role
        self.refused: list[str] = []  # "nodeid: reason" of each skip not accepted
        self.strict: set[str] = set()  # strict xfails: a known wrong answer, asserted still wrong

    def pytest_itemcollected(self, item: pytest.Item) -> None:
        """Remember strict xfails: they fail the run the day they pass, so they hide nothing."""
        marker = item.get_closest_marker("xfail")
        if marker is not None and marker.kwargs.get("strict"):
            self.strict.add(item.nodeid)

    def _note(self, report: pytest.CollectReport | pytest.TestReport) -> None:
        """Keep report's skip when it is not accepted."""
        if self.role == "controller":
            return
        if report.skipped and not hasattr(report, "wasxfail"):
            reason = skip_reason(report)
            if not accepted(reason, self.data_present):
                self.refused.append(f"{report.nodeid}: {reason}")

    def pytest_collectreport(self, report: pytest.CollectReport) -> None:
        """A module skipped as a whole (pytest.skip at import, a module-level skipif)."""
        self._note(report)

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        """A test skipped in setup (skipif) or in its body (pytest.skip). A non-strict xfail
        in CI hides a failure as well as a skip does: it is refused too."""
        if self.role != "controller" and hasattr(report, "wasxfail") \
                and report.when == "call" and report.nodeid not in self.strict:
            self.refused.append(f"{report.nodeid}: xfail ({report.wasxfail})")
        self._note(report)

    @pytest.hookimpl(optionalhook=True)
    def pytest_testnodedown(self, node, error) -> None:
        """xdist controller: take in what a finished worker refused."""
        seen = set(self.refused)  # a module skipped at collection is seen by every worker
        self.refused.extend(line for line in getattr(node, "workeroutput", {}).get(WORKER_KEY, [])
                            if line not in seen)

    @pytest.hookimpl(trylast=True)
    def pytest_sessionfinish(self, session: pytest.Session) -> None:
        """In CI, a run that refused a skip fails (exit status 1) even if every test passed;
        an xdist worker hands its refusals to the controller instead."""
        if self.role == "worker":
            session.config.workeroutput[WORKER_KEY] = list(self.refused)
            return
        if self.enforce and self.refused and session.exitstatus == pytest.ExitCode.OK:
            session.exitstatus = pytest.ExitCode.TESTS_FAILED

    def pytest_terminal_summary(self, terminalreporter) -> None:
        """List the skips CI refuses, and why the run failed for them."""
        if not (self.enforce and self.refused):
            return
        terminalreporter.section("skips refused in CI", sep="=", red=True, bold=True)
        for line in self.refused:
            terminalreporter.write_line(line)
        terminalreporter.write_line(
            f"CI accepts only skips whose reason starts with {DATA_ABSENT!r} (only while that "
            f"folder is absent) or is {COMPARE_EXTRA!r}: install what is missing (./.ci/setup).")
