#!/usr/bin/env python3
"""Read an hpr-mc campaign's Parquet files as an analyst would, and check them.

    python .ci/analyst_check.py RESULTS_DIR

RESULTS_DIR is a campaign's output directory (results/<name>/ by default). It must hold
variants.parquet and summary.parquet (an unsharded run), or variants-shard-K-of-N.parquet
files (a sharded run), or both (then they must hold the same rows).

Checks, with pyarrow, Polars and DuckDB (pip install pyarrow polars duckdb):
  * pyarrow: the schema (ids, status, error, the metrics), a "unit" in the field metadata of
    every float column, the hpr_mc.* file metadata, and the row count = sweep points x
    variants per point (from that metadata);
  * Polars: no nulls in the flight metrics of landed rows (the shift_* metrics may be null:
    a shift whose trigger never fired), and the per-point mean of every metric recomputed
    from the landed rows equal to summary.parquet's to 1e-9 relative, and each count of
    requirements.parquet (variants meeting a requirement) recounted from the rows;
  * DuckDB: every shard part read as one table with a glob: each variant id once, the count
    right, and (when there is an unsharded file too) the same rows; each landing ellipse of
    ellipses.parquet (the rocket's, and each released part's: body "release_<name>")
    centered on the mean of its landed rows' landing points, its count theirs.

Exits 0 when every check passes, 1 with a message naming the failed check otherwise.
"""

import glob
import math
import os
import sys

import duckdb
import polars as pl
import pyarrow.parquet as pq

WARNING_FLAGS = ["warning_unstable", "warning_large_alpha", "warning_ballistic"]
FIXED_METRICS = [
    "apogee_m", "apogee_time_s", "max_speed_m_s", "max_mach", "max_accel_m_s2", "max_dynamic_pressure_pa",
    "rail_exit_speed_m_s", "static_margin_liftoff_cal", "static_margin_rail_exit_cal",
    "static_margin_burnout_cal", "static_margin_min_cal", "flight_margin_min_cal",
    "max_alpha_deg", "landing_time_s", "landing_x_m", "landing_y_m", "landing_distance_m", "landing_speed_m_s",
]


def fail(msg):
    print(f"analyst check FAILED: {msg}", file=sys.stderr)
    sys.exit(1)


def check_file(path):
    """pyarrow: schema, units, metadata, row count. Returns the file's hpr_mc metadata."""
    pf = pq.ParquetFile(path)
    schema = pf.schema_arrow
    kv = {k.decode(): v.decode() for k, v in (pf.metadata.metadata or {}).items()}
    for key in ("hpr_mc.version", "hpr_mc.scenario", "hpr_mc.scenario_hash", "hpr_mc.seed",
                "hpr_mc.points", "hpr_mc.variants_per_point", "hpr_mc.shard"):
        if key not in kv:
            fail(f"{path}: no {key} in the file metadata")
    names = schema.names
    for col in ["variant_id", "point", "replicate", "status", "error", "warnings"] + WARNING_FLAGS + FIXED_METRICS:
        if col not in names:
            fail(f"{path}: no column {col}")
    for field in schema:
        if str(field.type) == "double":
            unit = (field.metadata or {}).get(b"unit")
            if not unit:
                fail(f"{path}: column {field.name} has no unit in its metadata")
    if (schema.field("apogee_m").metadata or {}).get(b"unit") != b"m":
        fail(f"{path}: apogee_m's unit is not m")
    total = int(kv["hpr_mc.points"]) * int(kv["hpr_mc.variants_per_point"])
    k, n = (int(x) for x in kv["hpr_mc.shard"].split("/"))
    expected = len(range(k, total, n))
    if pf.metadata.num_rows != expected:
        fail(f"{path}: {pf.metadata.num_rows} rows, expected {expected} (shard {k}/{n} of {total})")
    return kv, total


def check_means(variants_path, summary_path):
    """Polars: landed rows have every flight metric; the summary's means are theirs."""
    v = pl.read_parquet(variants_path)
    s = pl.read_parquet(summary_path)
    landed = v.filter(pl.col("status") == "landed")
    for col in FIXED_METRICS:
        nulls = landed[col].null_count()
        if nulls:
            fail(f"{variants_path}: {nulls} landed rows have no {col}")
    # Each warning flag is true exactly where the warnings text names its key; a landed
    # variant has every flag, a refused one none.
    for flag in WARNING_FLAGS:
        if landed[flag].null_count() or v.filter(pl.col("status") == "refused")[flag].null_count() != (v["status"] == "refused").sum():
            fail(f"{variants_path}: {flag} is null on a landed row or set on a refused one")
        flown = v.filter(pl.col(flag).is_not_null())
        key = flag.removeprefix("warning_")
        named = flown["warnings"].fill_null("").str.contains(f"(^|; ){key}:")
        if not (flown[flag] == named).all():
            fail(f"{variants_path}: {flag} disagrees with the warnings text")
    metrics = s["metric"].unique().to_list()
    means = landed.group_by("point").agg([pl.col(m).mean().alias(m) for m in metrics])
    checked = 0
    for row in s.iter_rows(named=True):
        if row["mean"] is None:
            continue
        mine = means.filter(pl.col("point") == row["point"])[row["metric"]]
        if len(mine) != 1 or mine[0] is None:
            fail(f"{summary_path}: point {row['point']} {row['metric']} has a mean but no landed value")
        a, b = mine[0], row["mean"]
        if not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12):
            fail(f"point {row['point']} {row['metric']}: mean {a} from the rows, {b} in the summary")
        checked += 1
    counts = landed.group_by("point").len()
    for row in s.filter(pl.col("metric") == "apogee_m").iter_rows(named=True):
        n = counts.filter(pl.col("point") == row["point"])["len"]
        landed_n = n[0] if len(n) else 0
        if row["variants"] - row["failures"] != landed_n:
            fail(f"point {row['point']}: summary says {row['variants']} variants, {row['failures']} failures; the rows say {landed_n} landed")
    return checked


def check_requirements(variants_path, requirements_path):
    """Polars: each requirement's count of variants meeting it, recounted from the rows (all
    statuses; a null metric does not meet it), and the fraction met / variants."""
    if not os.path.exists(requirements_path):
        fail(f"{requirements_path}: missing")
    v = pl.read_parquet(variants_path)
    r = pl.read_parquet(requirements_path)
    for row in r.iter_rows(named=True):
        rows = v.filter(pl.col("point") == row["point"])
        ok = pl.col(row["metric"]).is_not_null()
        if row["min"] is not None:
            ok = ok & (pl.col(row["metric"]) >= row["min"])
        if row["max"] is not None:
            ok = ok & (pl.col(row["metric"]) <= row["max"])
        met = rows.filter(ok).height
        if (met, rows.height) != (row["met"], row["variants"]):
            fail(f"{requirements_path}: point {row['point']} {row['metric']}: {row['met']} of {row['variants']} written, {met} of {rows.height} in the rows")
        if not (row["fraction_low_95"] <= row["fraction"] <= row["fraction_high_95"]) or not math.isclose(row["fraction"], met / rows.height, rel_tol=1e-15):
            fail(f"{requirements_path}: point {row['point']} {row['metric']}: fraction {row['fraction']} or its interval is wrong")
    return r.height


def check_ellipses(variants_path, ellipses_path):
    """DuckDB: each body's 1-sigma ellipse centered on the mean landing point of the point's
    landed rows that have one (the rocket's landing_x_m / landing_y_m, a released part's
    release_<name>_landing_x_m / _y_m), over as many rows."""
    con = duckdb.connect()
    rows = con.execute(
        f"SELECT point, body, count, center_x_m, center_y_m FROM read_parquet('{ellipses_path}') WHERE sigma = 1"
    ).fetchall()
    for point, body, count, cx, cy in rows:
        prefix = "" if body == "rocket" else f"{body}_"
        x, y = f"{prefix}landing_x_m", f"{prefix}landing_y_m"
        n, mx, my = con.execute(
            f"SELECT count(*), avg({x}), avg({y}) FROM read_parquet('{variants_path}') "
            f"WHERE point = {point} AND status = 'landed' AND {x} IS NOT NULL AND {y} IS NOT NULL"
        ).fetchone()
        if n != count or not (math.isclose(mx, cx, rel_tol=1e-9, abs_tol=1e-9) and math.isclose(my, cy, rel_tol=1e-9, abs_tol=1e-9)):
            fail(f"{ellipses_path}: point {point} {body}: {count} rows centered at ({cx}, {cy}); the rows give {n} at ({mx}, {my})")
    return len(rows)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    d = sys.argv[1]
    whole = os.path.join(d, "variants.parquet")
    shards = sorted(glob.glob(os.path.join(d, "variants-shard-*-of-*.parquet")))
    if not os.path.exists(whole) and not shards:
        fail(f"{d}: no variants.parquet and no variants-shard-K-of-N.parquet")
    total = None
    if os.path.exists(whole):
        kv, total = check_file(whole)
        checked = check_means(whole, os.path.join(d, "summary.parquet"))
        reqs = check_requirements(whole, os.path.join(d, "requirements.parquet"))
        ellipses = check_ellipses(whole, os.path.join(d, "ellipses.parquet"))
        print(f"{whole}: {total} rows, schema and units ok, {checked} summary means match, {reqs} requirement counts match, {ellipses} ellipses centered on their rows")
    if shards:
        ns = {os.path.basename(p).rsplit("-of-", 1)[1] for p in shards}
        if len(ns) != 1:
            fail(f"{d}: shard files of different N: {ns}")
        n = int(ns.pop().split(".")[0])
        if len(shards) != n:
            fail(f"{d}: {len(shards)} shard files for N = {n}")
        for p in shards:
            kv_s, total_s = check_file(p)
            check_means(p, p.replace("variants-shard", "summary-shard"))
            check_requirements(p, p.replace("variants-shard", "requirements-shard"))
            total = total_s if total is None else total
            if total_s != total:
                fail(f"{p}: {total_s} variants in its run, {total} in the others")
        con = duckdb.connect()
        parts = os.path.join(d, "variants-shard-*-of-*.parquet")
        count, distinct, lo, hi = con.execute(
            f"SELECT count(*), count(DISTINCT variant_id), min(variant_id), max(variant_id) FROM read_parquet('{parts}')"
        ).fetchone()
        if (count, distinct, lo, hi) != (total, total, 0, total - 1):
            fail(f"the shards hold {count} rows, {distinct} distinct ids from {lo} to {hi}; expected each of 0..{total - 1} once")
        if os.path.exists(whole):
            diff = con.execute(
                f"SELECT count(*) FROM ((SELECT * FROM read_parquet('{parts}') EXCEPT SELECT * FROM read_parquet('{whole}')) "
                f"UNION ALL (SELECT * FROM read_parquet('{whole}') EXCEPT SELECT * FROM read_parquet('{parts}')))"
            ).fetchone()[0]
            if diff:
                fail(f"the shards and {whole} differ in {diff} rows")
            print(f"{len(shards)} shards read as one table by DuckDB: {count} rows, the same as {whole}")
        else:
            print(f"{len(shards)} shards read as one table by DuckDB: {count} rows, each id once")
    print("analyst check ok")


if __name__ == "__main__":
    main()
