"""The streamed percentiles of a run past the exact size, against the exact type-7 percentiles
of its own variants.parquet: the largest rank error (a fraction of the point's count) and the
largest difference in value (a fraction of the point's 5-95 % range) over every point, metric
and percentile. Usage: python digest_check.py RESULTS_DIR
"""
import sys

import numpy as np
import pyarrow.parquet as pq

d = sys.argv[1]
v = pq.read_table(f"{d}/variants.parquet")
s = pq.read_table(f"{d}/summary.parquet").to_pylist()
print(pq.read_metadata(f"{d}/summary.parquet").metadata[b"hpr_mc.percentiles"].decode())
point = v.column("point").to_numpy()
keep = np.array(v.column("status").to_pylist()) == "landed"
worst_rank, worst_value, n_checked = (0.0, ""), (0.0, ""), 0
for row in s:
    col = v.column(row["metric"]).to_numpy(zero_copy_only=False).astype(float)
    x = col[keep & (point == row["point"])]
    x = x[np.isfinite(x)]
    if len(x) < 2:
        continue
    x.sort()
    span = np.quantile(x, 0.95) - np.quantile(x, 0.05)
    for q in ("p1", "p5", "p50", "p95", "p99"):
        est, qq = row[q], int(q[1:]) / 100
        exact = np.quantile(x, qq)  # type 7
        target = (len(x) - 1) * qq
        lo, hi = np.searchsorted(x, est, "left"), np.searchsorted(x, est, "right")
        lo_pos, hi_pos = (lo, hi - 1) if hi > lo else (max(lo - 1, 0), min(lo, len(x) - 1))
        off = max(lo_pos - target, target - hi_pos, 0) / len(x)
        where = f"point {row['point']} {row['metric']} {q}"
        if off > worst_rank[0]:
            worst_rank = (off, where)
        if span > 0 and abs(est - exact) / span > worst_value[0]:
            worst_value = (abs(est - exact) / span, where)
        n_checked += 1
print(f"{n_checked} percentiles checked; largest rank error {worst_rank[0]:.2e} of the count "
      f"({worst_rank[1]}); largest difference {worst_value[0]:.2e} of the 5-95 % range "
      f"({worst_value[1]})")
