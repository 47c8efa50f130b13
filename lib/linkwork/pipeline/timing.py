"""Wall-clock timing for accuracy-vs-cost studies and benchmarks (kept out of result files)."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable


def median_time(fn: Callable[[], object], repeats: int, warmup: bool = True) -> float:
    """Median wall-clock time (s, time.perf_counter) of ``repeats`` calls, after one warm-up call."""
    if warmup:
        fn()
    samples = []
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        fn()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def run_and_time(fn: Callable[[], object], repeats: int) -> tuple[object, float]:
    """(result of the first call, median wall-clock time of ``repeats`` calls); for a step whose result is
    needed anyway, so that the first timed call is also the one that produces it (no separate warm-up)."""
    samples, result = [], None
    for k in range(max(1, repeats)):
        start = time.perf_counter()
        out = fn()
        samples.append(time.perf_counter() - start)
        if k == 0:
            result = out
    return result, statistics.median(samples)
