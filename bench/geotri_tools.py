"""Running the geotri tools from the benchmark scripts: where a build keeps them, and one run with its JSON summary."""
import json
import subprocess
import time


def tool_path(build, tool):
    """geotri-TOOL in BUILD/tools (a build folder) or in BUILD itself (a folder of tools)."""
    nested = build / "tools" / f"geotri-{tool}"
    return nested if nested.exists() else build / f"geotri-{tool}"


def run(tool, args, build, timeout):
    """Runs geotri-TOOL with --json --quiet; returns (exit code, parsed JSON or None, wall seconds, stderr). A run
    that takes longer than `timeout` seconds is stopped: no JSON, and stderr says so."""
    start = time.perf_counter()
    try:
        done = subprocess.run([str(tool_path(build, tool)), "--json", "--quiet", *args],
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, None, time.perf_counter() - start, f"stopped after {timeout:.0f} s"
    seconds = time.perf_counter() - start
    try:
        summary = json.loads(done.stdout) if done.stdout.strip() else None
    except json.JSONDecodeError:
        summary = None
    return done.returncode, summary, seconds, done.stderr.strip()
