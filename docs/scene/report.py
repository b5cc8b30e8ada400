"""Summarises target/scene/out/<variant>-r<k>/ (docs/scene/run.sh) as the
markdown table of docs/tradeoff.md (section 3): one row per variant named on the
command line (default: all), timings over its repetitions (mean, and
min–max when more than one), results from the first repetition (runs are
deterministic: the steps and the peak of every repetition are checked to
agree). The step cost is (run CPU − setup CPU) / steps, the setup CPU being
the mean of docs/scene/setup.sh's `femdem check` runs of the variant."""
import collections
import csv
import pathlib
import re
import sys

S = pathlib.Path("target/scene/out")


def seconds(text, key):
    """A time of /usr/bin/time -v's report (s, or h:mm:ss / m:ss)."""
    v = re.search(r"^\s*" + key + r".*: ([\d.:]+)$", text, re.M).group(1).split(":")
    return sum(float(x) * 60**i for i, x in enumerate(reversed(v)))


def one(d):
    text = (d / "summary.txt").read_text() + (d / "time.txt").read_text()
    head = re.search(r"femdem: (\d+) tets \((\d+) deformable\), (\d+) joints, (\d+) nodes", text)
    # history.csv starts with `#` lines naming the case: skip them.
    rows = list(csv.DictReader(l for l in open(d / "history.csv") if not l.startswith("#")))
    load = [float(r["load"]) for r in rows] if "load" in rows[0] else [float("nan")]
    return dict(
        tets=int(head.group(2)),
        joints=int(head.group(3)),
        nodes=int(head.group(4)),
        steps=int(re.search(r"finished after (\d+) steps", text).group(1)),
        cpu=seconds(text, "User time") + seconds(text, "System time"),
        wall=seconds(text, "Elapsed"),
        rss=float(re.search(r"Maximum resident set size \(kbytes\): (\d+)", text).group(1)) / 1024,
        peak=max(load) / 1e3,
        fails=list(csv.DictReader(open(d / "failures.csv"))),
        load=[float(x) for x in re.findall(r"load average: ([\d.]+)", (d / "load.txt").read_text())],
    )


def setup_cpu(name):
    """Mean CPU s of `femdem check` on the variant, 0 if not measured."""
    texts = [f.read_text() for f in (S.parent / "setup").glob(name + "-r*.txt")]
    cpu = [seconds(t, "User time") + seconds(t, "System time") for t in texts]
    return sum(cpu) / len(cpu) if cpu else 0.0


runs = collections.defaultdict(list)
for d in sorted(S.iterdir()):
    summary = d / "summary.txt"
    if summary.exists() and "finished after" in summary.read_text():  # else running or failed
        runs[re.sub(r"-r\d+$", "", d.name)].append(one(d))
names = sys.argv[1:] or list(runs)
print("| variant | deformable tets | joints | nodes | steps | CPU s | setup CPU s | step CPU µs/step | wall s "
      "| max RSS MiB | peak load kN | failed joints (tensile/shear/mixed) | share within 2 mm of x = 0 |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for n in names:
    rs = runs[n]
    r = rs[0]
    assert all(q["steps"] == r["steps"] and (q["peak"] == r["peak"] or q["peak"] != q["peak"]) for q in rs), n
    setup = setup_cpu(n)
    for q in rs:
        q["us"] = 1e6 * (q["cpu"] - setup) / q["steps"]

    def span(k, f="{:.1f}"):
        mean = f.format(sum(q[k] for q in rs) / len(rs))
        return mean + (f" ({f.format(min(q[k] for q in rs))}–{f.format(max(q[k] for q in rs))})" if len(rs) > 1 else "")

    modes = [sum(f["mode"] == m for f in r["fails"]) for m in "123"]
    near = sum(abs(float(f["x"])) < 2e-3 for f in r["fails"]) / max(len(r["fails"]), 1)
    print(f"| {n} | {r['tets']} | {r['joints']} | {r['nodes']} | {r['steps']} | {span('cpu')} | {setup:.2f} "
          f"| {span('us', '{:.0f}')} | {span('wall')} | {max(q['rss'] for q in rs):.1f} | {r['peak']:.3f} "
          f"| {len(r['fails'])} ({modes[0]}/{modes[1]}/{modes[2]}) | {near:.2f} |")
loads = [x for n in names for q in runs[n] for x in q["load"]]
print(f"\nLoad average (1 min) before and after the runs: {min(loads):.1f} to {max(loads):.1f} on 2 cores; "
      f"{sum(len(runs[n]) for n in names)} runs.")
