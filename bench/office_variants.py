#!/usr/bin/env python3
"""The office sample's reflected components against path-traced references, variant by variant.

README ("daylit df", the comparison with long path-traced runs) quotes how far the radiosity's
mean IRC lies from the reference on the office sample and on variants of it that take parts
away (the glazing, the exterior surfaces, some interior reflectances), and how that changes when
the elements are halved. This script makes those variants from samples/office, runs
`daylit bench reflections` on each (its office case: every 30th sensor of grid.pts against a
path-traced run, N = 65,536, B = 16) and `daylit df --components all` on the same sensors at each
element size, and writes one row per variant and size to office_variants_<transport>.csv:

    variant, transport, element_size, grading, reference_irc_percent, reference_irc_standard_error,
    radiosity_irc_percent, relative_difference, rms_difference, sensors_covered,
    worst_irc_relative, sensors_beyond_3_sigma

(rms_difference: of ERC + IRC against the reference over the sensors, DF points; sensors_covered:
where |radiosity - reference| of ERC + IRC <= the estimate + 2 standard errors; worst_irc_relative:
the largest relative IRC difference at one sensor; sensors_beyond_3_sigma: where the IRC differs
by more than three of the reference's standard errors, which are about 1.4 % of the IRC per
sensor). About 2-3 minutes
per variant for the reference (kept and reused with --reuse-references) and 0.5-3 minutes per
radiosity run on 2 cores.

    bench/office_variants.py --daylit build/bin/daylit --out /tmp/office_variants [--variants a,b]
        [--transport collocated|reciprocal] [--reuse-references]
"""

import argparse
import csv
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
EXTERIOR = ("overhang_", "opposite_", "ground")  # polygon names (prefixes) outside the room

# name: (polygons dropped (name prefixes), materials made black, window open instead of glazed)
VARIANTS = {
    "sample": ((), (), False),
    "window_open": ((), (), True),
    "window_open_reveals_black": ((), ("frame_mat",), True),
    "no_exterior": (EXTERIOR, (), False),
    "no_exterior_open": (EXTERIOR, (), True),
    "no_exterior_open_reveals_black": (EXTERIOR, ("frame_mat",), True),
    "ground_only_exterior": (("overhang_", "opposite_"), (), False),
    "overhang_only_exterior": (("opposite_", "ground"), (), False),
    "opposite_only_exterior": (("overhang_", "ground"), (), False),
    "ceiling_only_inside_open": ((), ("floor_mat", "wall_mat", "frame_mat"), True),
    "reveals_only_inside_open": ((), ("floor_mat", "wall_mat", "ceiling_mat"), True),
    "reveals_only_exterior_black_open": ((), ("floor_mat", "wall_mat", "ceiling_mat", "facade_mat", "ground_mat"), True),
    "reveals_only_ground_only_exterior_open": (("overhang_", "opposite_"), ("floor_mat", "wall_mat", "ceiling_mat"), True),
    "reveals_only_overhang_only_exterior_open": (("opposite_", "ground"), ("floor_mat", "wall_mat", "ceiling_mat"), True),
    "walls_only_inside_open": ((), ("floor_mat", "ceiling_mat", "frame_mat"), True),
    "walls_only_inside_no_exterior_open": (EXTERIOR, ("floor_mat", "ceiling_mat", "frame_mat"), True),
    "floor_ceiling_only_no_exterior_open": (EXTERIOR, ("wall_mat", "frame_mat"), True),
}


def primitives(text):
    """Radiance primitives as token lists (comments dropped): modifier type name, then the
    string, integer and real argument lists, each led by its count."""
    tokens = []
    for line in text.splitlines():
        line = line.split("#", 1)[0]
        tokens += line.split()
    out, i = [], 0
    while i < len(tokens):
        start = i
        i += 3
        for _ in range(3):
            i += 1 + int(tokens[i])
        out.append(tokens[start:i])
    return out


def write(prims, path):
    with open(path, "w") as f:
        for p in prims:
            f.write(" ".join(p[:3]) + "\n")
            i = 3
            for _ in range(3):
                n = int(p[i])
                f.write(" ".join(p[i:i + 1 + n]) + "\n")
                i += 1 + n
            f.write("\n")


def make_variant(samples, out, dropped, black, window_open):
    os.makedirs(os.path.join(out, "office"), exist_ok=True)
    with open(os.path.join(samples, "office", "scene.rad")) as f:
        scene = primitives(f.read())
    kept = []
    for p in scene:
        if p[1] == "polygon" and any(p[2].startswith(d) for d in dropped):
            continue
        if p[1] == "plastic" and p[2] in black:
            p = p[:3] + ["0", "0", "5", "0", "0", "0", "0", "0"]
        kept.append(p)
    write(kept, os.path.join(out, "office", "scene.rad"))
    with open(os.path.join(samples, "office", "apertures.rad")) as f:
        apertures = primitives(f.read())
    if window_open:  # the glazing's polygons become openings (void: transmittance 1)
        apertures = [["void"] + p[1:] for p in apertures if p[1] == "polygon"]
    write(apertures, os.path.join(out, "office", "apertures.rad"))
    with open(os.path.join(samples, "office", "grid.pts")) as f:
        lines = [l for l in f if l.strip()]
    with open(os.path.join(out, "office", "grid.pts"), "w") as f:
        f.writelines(lines)
    with open(os.path.join(out, "every30.pts"), "w") as f:
        f.writelines(lines[::30])  # the bench's office case: sensors 0, 30, 60, ...


def compare(reference_csv, radiosity_csv):
    ref = [r for r in csv.DictReader(open(reference_csv)) if r["case"] == "office"]
    rad = list(csv.DictReader(open(radiosity_csv)))
    if len(ref) != len(rad):
        sys.exit(f"{radiosity_csv}: {len(rad)} sensors against the reference's {len(ref)}")
    covered, squares, worst, beyond = 0, 0.0, 0.0, 0
    for a, b in zip(rad, ref):
        if abs(float(a["x"]) - float(b["x"])) > 1e-9 or abs(float(a["y"]) - float(b["y"])) > 1e-9:
            sys.exit(f"{radiosity_csv}: sensor {a['index']} is not the reference's")
        diff = float(a["erc_percent"]) + float(a["irc_percent"]) - float(b["erc_percent"]) - float(b["irc_percent"])
        sigma = math.hypot(float(b["erc_se"]), float(b["irc_se"]))
        covered += abs(diff) <= float(a["reflection_error_estimate_percent"]) + 2 * sigma
        squares += diff * diff
        irc_diff = float(a["irc_percent"]) - float(b["irc_percent"])
        if float(b["irc_percent"]) > 0 and abs(irc_diff) > abs(worst) * float(b["irc_percent"]):
            worst = irc_diff / float(b["irc_percent"])
        beyond += abs(irc_diff) > 3 * float(b["irc_se"])
    n = len(ref)
    ref_irc = sum(float(b["irc_percent"]) for b in ref) / n
    ref_se = math.sqrt(sum(float(b["irc_se"]) ** 2 for b in ref)) / n
    irc = sum(float(a["irc_percent"]) for a in rad) / n
    return ref_irc, ref_se, irc, math.sqrt(squares / n), covered, n, worst, beyond


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--daylit", required=True)
    parser.add_argument("--samples", default=os.path.join(HERE, "..", "samples"))
    parser.add_argument("--out", required=True)
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--sizes", default="1.18,0.59", help="element sizes (model units)")
    parser.add_argument("--grading", type=float, default=0.5)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--transport", choices=("collocated", "reciprocal"), default="reciprocal")
    parser.add_argument("--reuse-references", action="store_true",
                        help="keep a variant's reference from an earlier run of the same --out")
    args = parser.parse_args()
    rows = []
    for name in args.variants.split(","):
        if name not in VARIANTS:
            sys.exit(f"unknown variant '{name}' (known: {', '.join(VARIANTS)})")
        out = os.path.join(args.out, name)
        make_variant(args.samples, out, *VARIANTS[name])
        bench = os.path.join(out, "bench")
        reference = os.path.join(bench, "reflections_reference.csv")
        if not (args.reuse_references and os.path.exists(reference)):
            subprocess.run([args.daylit, "bench", "reflections", "--samples", out, "--out", bench, "--quiet"], check=True)
        office = os.path.join(out, "office")
        for size in args.sizes.split(","):
            result = os.path.join(out, f"radiosity_{args.transport}_{size}.csv")
            subprocess.run([args.daylit, "df", "--scene", os.path.join(office, "scene.rad"), "--apertures",
                            os.path.join(office, "apertures.rad"), "--grid", os.path.join(out, "every30.pts"),
                            "--components", "all", "--element-size", size, "--element-grading", str(args.grading),
                            "--reflection-transport", args.transport,
                            "--threads", str(args.threads), "--quiet", "--out", result], check=True)
            ref_irc, ref_se, irc, rms, covered, n, worst, beyond = compare(reference, result)
            rows.append([name, args.transport, size, args.grading, f"{ref_irc:.5f}", f"{ref_se:.5f}", f"{irc:.5f}",
                         f"{irc / ref_irc - 1:+.4f}" if ref_irc > 0 else "", f"{rms:.4f}", f"{covered}/{n}",
                         f"{worst:+.4f}", beyond])
            print(",".join(map(str, rows[-1])), flush=True)
    with open(os.path.join(args.out, f"office_variants_{args.transport}.csv"), "w") as f:
        f.write("variant,transport,element_size,grading,reference_irc_percent,reference_irc_standard_error,"
                "radiosity_irc_percent,relative_difference,rms_difference,sensors_covered,worst_irc_relative,"
                "sensors_beyond_3_sigma\n")
        for r in rows:
            f.write(",".join(map(str, r)) + "\n")


if __name__ == "__main__":
    main()
