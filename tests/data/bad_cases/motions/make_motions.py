#!/usr/bin/python3
"""Writes the ground-motion files of the bad cases next to this script: CSV
records and K-NET ASCII records (17 header lines, then 8 counts per line),
valid ones and each with one defect. The files are kept in the repository."""
import math
import pathlib

HERE = pathlib.Path(__file__).parent


def csv(name, rows, header="time_s,ax,ay,az"):
    (HERE / name).write_text(header + "\n" + "".join(",".join(str(v) for v in row) + "\n" for row in rows))


def uniform(n=50, dt=0.01):
    return [[round(i * dt, 10), round(0.1 * math.sin(i / 5), 6), 0, 0] for i in range(n)]


csv("gap.csv", uniform()[:20] + uniform()[23:])  # three samples missing after t = 0.19 s
csv("nan_value.csv", [r if i != 7 else [r[0], "nan", 0, 0] for i, r in enumerate(uniform())])
csv("wrong_header.csv", uniform(), header="t,ax,ay")
csv("short_row.csv", [r if i != 4 else r[:3] for i, r in enumerate(uniform())])
csv("time_backwards.csv", uniform()[:10] + [[0.05, 0, 0, 0]] + uniform()[10:])


def knet(name, frequency="100Hz", duration="2", scale="7845(gal)/8223790", samples=200, header_lines=17,
         corrupt=None):
    header = [("Origin Time", "2003/09/26 04:50:00"), ("Lat.", "41.780"), ("Long.", "144.078"),
              ("Depth. (km)", "42"), ("Mag.", "8.0"), ("Station Code", "HKD129"), ("Station Lat.", "42.6358"),
              ("Station Long.", "141.6061"), ("Station Height(m)", "5"), ("Record Time", "2003/09/26 04:50:20"),
              ("Sampling Freq(Hz)", frequency), ("Duration Time(s)", duration), ("Dir.", "N-S"),
              ("Scale Factor", scale), ("Max. Acc. (gal)", "10.0"), ("Last Correction", "2003/09/26 04:50:05"),
              ("Memo.", "")]
    lines = [f"{key:<18}{value}".rstrip() for key, value in header][:header_lines]
    counts = [str(int(1000 * math.sin(i / 7))) for i in range(samples)]
    if corrupt:
        counts = corrupt(counts)
    lines += [" ".join(counts[i:i + 8]) for i in range(0, len(counts), 8)]
    (HERE / name).write_text("\n".join(lines) + "\n")


knet("station.NS")
knet("station_50hz.EW", frequency="50Hz", samples=100)
knet("truncated_header.NS", header_lines=11, samples=0)
knet("nan_count.NS", corrupt=lambda c: c[:13] + ["NaN"] + c[14:])
knet("truncated_data.NS", duration="60")
knet("bad_scale.NS", scale="7845/8223790")
knet("bad_frequency.NS", frequency="fastHz")
# Found by fuzz_knet_record: counts this large overflowed the pre-event sum.
knet("huge_count.NS", corrupt=lambda c: c[:5] + ["6561111111111512541", "8375319363688624582"] + c[7:])
