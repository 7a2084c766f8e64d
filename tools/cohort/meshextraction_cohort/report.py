"""The summary (summary.csv: one row per case; summary.json: the totals and the rows) and the
HTML report: totals, the quality distribution over the cohort (inline SVG), the worst
cases, the failures with their messages, and every case with its time and memory."""

import csv
import html
import math
import os
import time

from . import outputs

COLUMNS = (
    "case",
    "status",
    "this_run",
    "attempts",
    "wall_seconds",
    "cpu_seconds",
    "max_rss_mb",
    "surfaces",
    "triangles",
    "q_area_mean",
    "q_angle_mean",
    "q_angle_min",
    "q_angle_below_0_3_percent",
    "valid",
    "worker",
    "message",
)


def _aggregate(surfaces):
    """One case's measures over its surfaces: sums, triangle-weighted means, minima."""
    measured = [s for s in surfaces if s.get("triangles")]
    triangles = sum(s["triangles"] for s in measured)
    if not triangles:
        return {}

    def weighted(key):
        return sum(s[key] * s["triangles"] for s in measured) / triangles

    return {
        "triangles": triangles,
        "q_area_mean": weighted("q_area_mean"),
        "q_angle_mean": weighted("q_angle_mean"),
        "q_angle_min": min(s["q_angle_min"] for s in measured),
        "q_angle_below_0_3_percent": 100.0 * weighted("q_angle_below_0_3"),
    }


def case_row(case, record, pending):
    """The summary row of one case."""
    if record is None:
        return {"case": case.case_id, "status": "not run", "this_run": "pending" if case.case_id in pending else "no"}
    row = {
        "case": case.case_id,
        "status": record["status"],
        "this_run": "computed" if record.get("computed") else "kept",
        "attempts": record.get("attempts"),
        "wall_seconds": record.get("wall_seconds"),
        "cpu_seconds": record.get("cpu_seconds"),
        "max_rss_mb": record.get("max_rss_mb"),
        "surfaces": len(record.get("surfaces", [])),
        "valid": "yes" if record["status"] == "ok" else "no",
        "worker": record.get("worker"),
        "message": record.get("message"),
    }
    row.update(_aggregate(record.get("surfaces", [])))
    return row


def _format(value):
    if isinstance(value, float):
        return f"{value:.6g}"
    return "" if value is None else str(value)


def totals_of(rows, description, started, run_id, args):
    computed = [r for r in rows if r.get("this_run") == "computed"]
    finished = time.time()
    totals = {
        "run_id": run_id,
        "manifest": os.path.abspath(args.manifest),
        "outdir": os.path.abspath(args.outdir),
        "scheduler": description,
        "started": time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(started)),
        "run_seconds": round(finished - started, 2),
        "cases": len(rows),
        "succeeded": sum(r["status"] == "ok" for r in rows),
        "failed": sum(r["status"] == "failed" for r in rows),
        "not_run": sum(r["status"] == "not run" for r in rows),
        "retried": sum((r.get("attempts") or 1) > 1 for r in computed),
        "computed": len(computed),
        "reused": sum(r.get("this_run") == "kept" for r in rows),
    }
    if computed:
        totals["task_seconds_mean"] = round(sum(r["wall_seconds"] or 0 for r in computed) / len(computed), 4)
        totals["task_max_rss_mb_max"] = max(r.get("max_rss_mb") or 0 for r in computed)
        totals["cases_per_minute"] = round(60.0 * len(computed) / max(totals["run_seconds"], 1e-9), 2)
    return totals


def write_all(args, cases, records, pending, description, started, run_id):
    """Writes summary.csv, summary.json and report.html; returns the totals."""
    rows = [case_row(case, records.get(case.case_id), pending) for case in cases]
    totals = totals_of(rows, description, started, run_id, args)
    temporary = os.path.join(args.outdir, f".summary.csv.tmp-{os.getpid()}")
    with open(temporary, "w", newline="", encoding="utf-8") as stream:
        writer = csv.DictWriter(stream, fieldnames=COLUMNS, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: _format(row.get(k)) for k in COLUMNS})
    os.replace(temporary, os.path.join(args.outdir, "summary.csv"))
    outputs.write_json_atomically(os.path.join(args.outdir, "summary.json"), {"totals": totals, "cases": rows})
    page = render(args.title, totals, rows, records)
    temporary = os.path.join(args.outdir, f".report.html.tmp-{os.getpid()}")
    with open(temporary, "w", encoding="utf-8") as stream:
        stream.write(page)
    os.replace(temporary, os.path.join(args.outdir, "report.html"))
    return totals


# ---------------------------------------------------------------------------------------
# SVG charts


def _nice_range(values):
    lo, hi = min(values), max(values)
    if hi - lo < 1e-12:
        pad = abs(lo) * 0.01 or 0.5
        return lo - pad, hi + pad
    step = 10 ** math.floor(math.log10(hi - lo) - 1)
    return math.floor(lo / step) * step, math.ceil(hi / step) * step


def _bins(values, bins, lo, hi):
    counts, members = [0] * bins, [[] for _ in range(bins)]
    for name, value in values:
        index = min(bins - 1, max(0, int((value - lo) / (hi - lo) * bins)))
        counts[index] += 1
        members[index].append(name)
    return counts, members


def svg_histogram(counts, lo, hi, title, xlabel, ylabel="cases", tooltips=None, width=380, height=210):
    """A bar chart of counts over equal bins of [lo, hi], with axes and tick labels."""
    left, right, top, bottom = 46, 14, 26, 40
    plot_w, plot_h = width - left - right, height - top - bottom
    peak = max(counts) if counts and max(counts) > 0 else 1
    e = html.escape
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">',
        f'<text x="{width / 2}" y="15" text-anchor="middle" font-size="12" font-weight="bold">{e(title)}</text>',
    ]
    bar_w = plot_w / len(counts)
    for i, count in enumerate(counts):
        h = plot_h * count / peak
        x, y = left + i * bar_w, top + plot_h - h
        tip = f"{lo + i * (hi - lo) / len(counts):.4g} to {lo + (i + 1) * (hi - lo) / len(counts):.4g}: {count}"
        if tooltips and tooltips[i]:
            more = f" and {len(tooltips[i]) - 12} more" if len(tooltips[i]) > 12 else ""
            tip += " (" + ", ".join(tooltips[i][:12]) + more + ")"
        parts.append(
            f'<rect x="{x + 1:.1f}" y="{y:.1f}" width="{max(bar_w - 2, 1):.1f}" height="{h:.1f}" '
            f'fill="#4a78b0"><title>{e(tip)}</title></rect>'
        )
    axis_y = top + plot_h
    parts.append(f'<line x1="{left}" y1="{axis_y}" x2="{left + plot_w}" y2="{axis_y}" stroke="#333"/>')
    parts.append(f'<line x1="{left}" y1="{top}" x2="{left}" y2="{axis_y}" stroke="#333"/>')
    for k in range(5):
        value, x = lo + k * (hi - lo) / 4, left + k * plot_w / 4
        parts.append(f'<line x1="{x:.1f}" y1="{axis_y}" x2="{x:.1f}" y2="{axis_y + 4}" stroke="#333"/>')
        parts.append(f'<text x="{x:.1f}" y="{axis_y + 15}" text-anchor="middle">{value:.4g}</text>')
    for k in range(3):
        value = peak * k / 2
        y = axis_y - plot_h * k / 2
        parts.append(f'<text x="{left - 5}" y="{y + 4:.1f}" text-anchor="end">{value:.3g}</text>')
    parts.append(f'<text x="{left + plot_w / 2}" y="{height - 6}" text-anchor="middle">{e(xlabel)}</text>')
    parts.append(
        f'<text x="12" y="{top + plot_h / 2}" text-anchor="middle" '
        f'transform="rotate(-90 12 {top + plot_h / 2})">{e(ylabel)}</text>'
    )
    parts.append("</svg>")
    return "".join(parts)


def _case_histogram(rows, key, title, xlabel, bins=20):
    values = [(r["case"], r[key]) for r in rows if r.get(key) is not None]
    if not values:
        return ""
    lo, hi = _nice_range([v for _, v in values])
    counts, members = _bins(values, bins, lo, hi)
    return svg_histogram(counts, lo, hi, title, xlabel, tooltips=members)


def _pooled_histogram(records, key, title):
    """The histogram of every triangle of the cohort: the sum of the meshes' histograms."""
    total = None
    for record in records.values():
        if record.get("status") != "ok":
            continue
        for surface in record.get("surfaces", []):
            counts = surface.get(key)
            if counts:
                total = list(counts) if total is None else [a + b for a, b in zip(total, counts)]
    if not total or not sum(total):
        return ""
    percent = [100.0 * c / sum(total) for c in total]
    return svg_histogram(percent, 0.0, 1.0, title, key.replace("_histogram", ""), ylabel="% of triangles")


# ---------------------------------------------------------------------------------------
# HTML

_STYLE = """
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1250px; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em 0; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: right; }
th { background: #eef2f7; } td.l, th.l { text-align: left; }
tr.failed td { background: #fbeaea; } pre { margin: 0; white-space: pre-wrap; font-size: 12px; text-align: left; }
.charts svg { margin: 0 12px 12px 0; border: 1px solid #e3e3e3; background: #fff; }
.totals td { text-align: left; } .bad { color: #b00020; font-weight: bold; }
"""


def _links(case_id, record):
    base = f"cases/{html.escape(case_id)}/"
    links = []
    for surface in (record or {}).get("surfaces", []) if (record or {}).get("status") == "ok" else []:
        links.append(f'<a href="{base}{html.escape(surface["mesh"])}">{html.escape(surface["mesh"])}</a>')
        links.append(f'<a href="{base}{html.escape(surface["quality_json"])}">quality</a>')
    if record is not None:
        links.append(f'<a href="{base}{html.escape(case_id)}.log">log</a>')
    return " ".join(links)


def _cell(value, digits=4):
    if value is None or value == "":
        return "<td></td>"
    if isinstance(value, float):
        return f"<td>{value:.{digits}f}</td>"
    return f"<td>{html.escape(str(value))}</td>"


def _totals_table(totals):
    failed = f'<span class="bad">{totals["failed"]}</span>' if totals["failed"] else "0"
    lines = [
        ("cases", totals["cases"]),
        (
            "succeeded",
            f'{totals["succeeded"]} ({totals["reused"]} kept from earlier runs, {totals["computed"]} computed)',
        ),
        ("failed", failed),
        ("retried (a worker died or the task raised)", totals["retried"]),
        ("not run (interrupted)", totals["not_run"]),
        ("scheduler", html.escape(totals["scheduler"])),
        ("run started, duration", f'{totals["started"]}, {totals["run_seconds"]} s'),
    ]
    if "task_seconds_mean" in totals:
        lines.append(
            (
                "computed cases",
                f'{totals["cases_per_minute"]} cases/min, mean {totals["task_seconds_mean"]} s per case, '
                f'peak memory of one task {totals["task_max_rss_mb_max"]} MB',
            )
        )
    lines.append(("manifest", html.escape(totals["manifest"])))
    body = "".join(f'<tr><th class="l">{html.escape(k)}</th><td>{v}</td></tr>' for k, v in lines)
    return f'<table class="totals">{body}</table>'


def _measure_cells(row):
    return (
        _cell(row.get("triangles"))
        + _cell(row.get("q_area_mean"))
        + _cell(row.get("q_angle_mean"))
        + _cell(row.get("q_angle_min"))
        + _cell(row.get("q_angle_below_0_3_percent"), 2)
    )


_MEASURE_HEADER = (
    "<th>triangles</th><th>mean q_area</th><th>mean q_angle</th><th>min q_angle</th><th>% q_angle &lt; 0.3</th>"
)


def _worst_table(rows, records, count=10):
    ok = sorted(
        (r for r in rows if r["status"] == "ok" and r.get("q_angle_min") is not None), key=lambda r: r["q_angle_min"]
    )
    if not ok:
        return "<p>No successful case.</p>"
    body = "".join(
        f'<tr><td class="l">{html.escape(r["case"])}</td>{_measure_cells(r)}'
        f'<td class="l">{_links(r["case"], records.get(r["case"]))}</td></tr>'
        for r in ok[:count]
    )
    return f'<table><tr><th class="l">case</th>{_MEASURE_HEADER}<th class="l">files</th></tr>{body}</table>'


def _failure_table(rows, records):
    failed = [r for r in rows if r["status"] == "failed"]
    if not failed:
        return "<p>None.</p>"
    body = "".join(
        f'<tr class="failed"><td class="l">{html.escape(r["case"])}</td><td>{_format(r.get("attempts"))}</td>'
        f'<td class="l"><pre>{html.escape(r.get("message") or "")}</pre></td>'
        f'<td class="l">{_links(r["case"], records.get(r["case"]))}</td></tr>'
        for r in failed
    )
    return f'<table><tr><th class="l">case</th><th>attempts</th><th class="l">message</th><th class="l">files</th></tr>{body}</table>'


def _all_table(rows, records):
    body = []
    for r in rows:
        css = ' class="failed"' if r["status"] != "ok" else ""
        body.append(
            f'<tr{css}><td class="l">{html.escape(r["case"])}</td><td class="l">{html.escape(r["status"])}</td>'
            f'<td class="l">{html.escape(r.get("this_run") or "")}</td>{_cell(r.get("attempts"))}'
            f'{_cell(r.get("wall_seconds"), 2)}{_cell(r.get("cpu_seconds"), 2)}{_cell(r.get("max_rss_mb"), 1)}'
            f'{_measure_cells(r)}<td class="l">{_links(r["case"], records.get(r["case"]))}</td></tr>'
        )
    return (
        '<table><tr><th class="l">case</th><th class="l">status</th><th class="l">this run</th><th>attempts</th>'
        f'<th>time s</th><th>CPU s</th><th>memory MB</th>{_MEASURE_HEADER}<th class="l">files</th></tr>'
        + "".join(body)
        + "</table>"
    )


def render(title, totals, rows, records):
    ok = [r for r in rows if r["status"] == "ok"]
    computed = [r for r in rows if r.get("this_run") == "computed"]
    charts_quality = [
        _pooled_histogram(records, "q_area_histogram", "q_area of every triangle of the cohort"),
        _pooled_histogram(records, "q_angle_histogram", "q_angle of every triangle of the cohort"),
        _case_histogram(ok, "q_area_mean", "mean q_area per case", "mean q_area"),
        _case_histogram(ok, "q_angle_mean", "mean q_angle per case", "mean q_angle"),
        _case_histogram(ok, "q_angle_min", "smallest q_angle per case", "min q_angle"),
        _case_histogram(
            ok, "q_angle_below_0_3_percent", "share of slivers per case", "% of triangles with q_angle < 0.3"
        ),
    ]
    charts_cost = [
        _case_histogram(computed, "wall_seconds", "time per case (this run)", "seconds"),
        _case_histogram(computed, "max_rss_mb", "peak memory per case (this run)", "MB (largest process of the case)"),
    ]
    e = html.escape
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{e(title)}</title><style>{_STYLE}</style></head>
<body>
<h1>{e(title)}</h1>
{_totals_table(totals)}
<h2>Quality over the cohort</h2>
<p>q_area = 4&radic;3&middot;A/&Sigma;e&sup2; and q_angle = smallest/largest angle are 1 for an equilateral triangle.
Hover a bar for its cases.</p>
<div class="charts">{"".join(charts_quality)}</div>
<h2>Worst cases (smallest q_angle)</h2>
{_worst_table(rows, records)}
<h2>Failures</h2>
{_failure_table(rows, records)}
<h2>Time and memory</h2>
<div class="charts">{"".join(charts_cost)}</div>
<h2>Every case</h2>
{_all_table(rows, records)}
<p>Made by meshextraction-cohort, run {e(totals["run_id"])}.</p>
</body></html>
"""
