"""Running the geotri tools from the benchmark scripts: where a build keeps them, and one run with its JSON summary."""
import json
import subprocess
import time


def tool_path(build, tool):
    """geotri-TOOL in BUILD/tools (a build folder) or in BUILD itself (a folder of tools)."""
    nested = build / "tools" / f"geotri-{tool}"
    return nested if nested.exists() else build / f"geotri-{tool}"


def command(tool, args, build):
    """The command line of geotri-TOOL with --json --quiet and `args`."""
    return [str(tool_path(build, tool)), "--json", "--quiet", *map(str, args)]


def summary_of(stdout):
    """A tool's --json summary from its stdout, or None."""
    try:
        return json.loads(stdout) if stdout.strip() else None
    except json.JSONDecodeError:
        return None


def run(tool, args, build, timeout):
    """Runs geotri-TOOL with --json --quiet; returns (exit code, parsed JSON or None, wall seconds, stderr). A run
    that takes longer than `timeout` seconds is stopped: no JSON, and stderr says so."""
    start = time.perf_counter()
    try:
        done = subprocess.run(command(tool, args, build), capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, None, time.perf_counter() - start, f"stopped after {timeout:.0f} s"
    seconds = time.perf_counter() - start
    return done.returncode, summary_of(done.stdout), seconds, done.stderr.strip()
