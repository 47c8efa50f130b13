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
