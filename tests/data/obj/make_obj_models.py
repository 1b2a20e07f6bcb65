#!/usr/bin/env python3
"""Writes the OBJ test models of tests/data/obj/ from the bundled .rad samples, polygon for
polygon and material for material, so that `daylit df --model X.obj` must give what the .rad
files give (tests/cli/cli_obj.sh, tests/geometry/test_obj_model.cpp):

  room.obj, room.mtl, room_map.json        samples/room (scene + apertures), z up, metres
  room_yup_mm.obj                          the same room, y up ((x, y, z) written as (x, z, -y))
                                           in millimetres, exact decimals (1000 times the metres'
                                           shortest decimal text: read back with --obj-scale 0.001
                                           each coordinate is the double nearest its metres)
  room_indices.obj                         the same room, every face with negative (relative)
                                           indices in the forms v/vt/vn, v//vn and v/vt, vertices
                                           repeated per face, with texture coordinates, normals,
                                           comments, smoothing groups, a line element and a
                                           continued line, as exporters write them
  office.obj, office.mtl, office_map.json  samples/office (scene + apertures), z up, metres

Coordinates are written with repr (the shortest text that reads back as the same double).
Plastics become Kd (their specularity must be 0: the map could not carry it otherwise); glass
becomes a material with d = 0.12 (0.88 at normal incidence without the map) that the map turns
back into Radiance's glass of the same transmissivity. Standard library only; deterministic.

Usage: tests/data/obj/make_obj_models.py  (writes beside itself)
"""
import decimal
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
samples = os.path.join(here, "..", "..", "..", "samples")


def read_rad(path):
    """Materials {name: (type, reals)} and polygons [(material, name, [(x, y, z)])], in order."""
    words = []
    for line in open(path):
        words += line.split("#", 1)[0].split()
    materials, polygons, i = {}, [], 0
    while i < len(words):
        modifier, kind, name = words[i:i + 3]
        i += 3
        nstr = int(words[i]); i += 1 + nstr
        nint = int(words[i]); i += 1 + nint
        nreal = int(words[i]); i += 1
        reals = [float(w) for w in words[i:i + nreal]]
        texts = words[i:i + nreal]
        i += nreal
        if kind == "polygon":
            polygons.append((modifier, name, [tuple(texts[k:k + 3]) for k in range(0, nreal, 3)]))
        else:
            materials[name] = (kind, reals)
    return materials, polygons


def write_mtl(path, materials):
    lines = ["# daylit test model: the materials of the .rad sample (make_obj_models.py)."]
    for name, (kind, reals) in materials.items():
        lines += ["", f"newmtl {name}"]
        if kind == "plastic":
            assert reals[3] == 0 and reals[4] == 0, "a plastic with specularity: Kd alone cannot carry it"
            lines += ["Ka 0 0 0", f"Kd {reals[0]!r} {reals[1]!r} {reals[2]!r}", "Ks 0 0 0", "Ns 10", "d 1", "illum 1"]
        elif kind == "glass":
            lines += ["Kd 0 0 0", "Ks 0 0 0", "d 0.12", "illum 4"]
        else:
            raise ValueError(kind)
    open(path, "w").write("\n".join(lines) + "\n")


def write_map(path, materials):
    rules = {}
    for name, (kind, reals) in materials.items():
        if kind == "glass":
            assert reals[0] == reals[1] == reals[2]
            rules[name] = {"role": "glass", "transmissivity": reals[0]}
        else:
            rules[name] = {"role": "opaque"}
    json.dump({"materials": rules}, open(path, "w"), indent=2)
    open(path, "a").write("\n")


def as_double(text):
    return repr(float(text))


def millimetres(text):
    """1000 times the decimal text of a metres coordinate, exactly, without an exponent."""
    d = decimal.Decimal(repr(float(text))) * 1000
    s = format(d.normalize(), "f")
    return "0" if s in ("-0", "0") else s


def write_obj(path, mtl, polygons, header, transform=None, indices=False):
    lines = [f"# daylit test model: {header} (make_obj_models.py).", f"mtllib {mtl}"]
    index = {}
    count = 0
    material = None
    for modifier, name, vertices in polygons:
        lines.append(f"g {name}")
        if modifier != material:
            lines.append(f"usemtl {modifier}")
            material = modifier
        if indices:
            # Every vertex again, just before its face, referenced by negative indices.
            refs = []
            for k, v in enumerate(vertices):
                lines.append("v " + " ".join(as_double(c) for c in v))
                lines.append(f"vt {0.25 * k!r} 0.5")
            lines.append("vn 0 0 1")
            lines.append("s off")
            n = len(vertices)
            forms = ["{v}/{t}/-1", "{v}//-1", "{v}/{t}"]
            for k in range(n):
                refs.append(forms[k % 3].format(v=k - n, t=k - n))
            if len(refs) > 6:  # a long face on two lines, joined by a backslash
                lines.append("f " + " ".join(refs[:4]) + " \\")
                lines.append("  " + " ".join(refs[4:]))
            else:
                lines.append("f " + " ".join(refs) + "  # relative indices")
            lines.append(f"l {-n} {-n + 1}")
            continue
        refs = []
        for v in vertices:
            key = tuple(float(c) for c in v)
            if key not in index:
                count += 1
                index[key] = count
                lines.append("v " + (transform(v) if transform else " ".join(as_double(c) for c in v)))
            refs.append(str(index[key]))
        lines.append("f " + " ".join(refs))
    open(path, "w").write("\n".join(lines) + "\n")


def model(sample, stem, variants):
    materials, polygons = {}, []
    for f in ("scene.rad", "apertures.rad"):
        m, p = read_rad(os.path.join(samples, sample, f))
        materials.update(m)
        polygons += p
    write_mtl(os.path.join(here, stem + ".mtl"), materials)
    write_map(os.path.join(here, stem + "_map.json"), materials)
    write_obj(os.path.join(here, stem + ".obj"), stem + ".mtl", polygons, f"samples/{sample}, z up, metres")
    if "yup_mm" in variants:
        write_obj(os.path.join(here, stem + "_yup_mm.obj"), stem + ".mtl", polygons,
                  f"samples/{sample}, y up, millimetres",
                  transform=lambda v: f"{millimetres(v[0])} {millimetres(v[2])} {millimetres('-' + v[1] if not v[1].startswith('-') else v[1][1:])}")
    if "indices" in variants:
        write_obj(os.path.join(here, stem + "_indices.obj"), stem + ".mtl", polygons,
                  f"samples/{sample}, relative indices and v/vt/vn forms", indices=True)


model("room", "room", {"yup_mm", "indices"})
model("office", "office", set())
