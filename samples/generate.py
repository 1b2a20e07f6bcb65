#!/usr/bin/env python3
"""Generates daylit's bundled sample scenes (samples/office, samples/hall).

Standard library only and deterministic: run it from anywhere, it rewrites every sample file next
to itself. All coordinates are kept internally as integer millimetres, so the files carry short
exact decimals and the checks below (planarity, area, self-intersection, orientation) are exact.

Orientation convention: every polygon's vertex order gives, by the right-hand rule, a normal that
points away from the solid it bounds (into the room for room surfaces, into the open air for
exterior faces). Apertures point into the room they light.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


# --------------------------------------------------------------------------------------------
# Numbers: integer millimetres in, short decimal metres out.

def mm(metres):
    """Metres (int, float or str) to integer millimetres, exactly for the decimals used here."""
    value = round(float(metres) * 1000)
    assert abs(value - float(metres) * 1000) < 1e-6, metres
    return value


def fmt(v_mm):
    """Integer millimetres as the shortest decimal metres: 1250 -> '1.25', -300 -> '-0.3'."""
    sign = "-" if v_mm < 0 else ""
    whole, frac = divmod(abs(v_mm), 1000)
    if frac == 0:
        return f"{sign}{whole}"
    return f"{sign}{whole}.{frac:03d}".rstrip("0")


def P(x, y, z):
    return (mm(x), mm(y), mm(z))


# --------------------------------------------------------------------------------------------
# Exact polygon checks.

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def newell(vs):
    """Twice the vector area of a closed loop (exact with integer vertices)."""
    n = [0, 0, 0]
    for i, a in enumerate(vs):
        b = vs[(i + 1) % len(vs)]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return tuple(n)


def orient2(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def on_segment(a, b, p):
    """p collinear with a-b: is it within the closed segment?"""
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def segments_meet(a, b, c, d):
    """Do closed segments ab and cd share any point?"""
    o1, o2, o3, o4 = orient2(a, b, c), orient2(a, b, d), orient2(c, d, a), orient2(c, d, b)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    return ((o1 == 0 and on_segment(a, b, c)) or (o2 == 0 and on_segment(a, b, d))
            or (o3 == 0 and on_segment(c, d, a)) or (o4 == 0 and on_segment(c, d, b)))


def check_polygon(name, vs, facing):
    """Raises AssertionError unless the polygon is valid and its normal points along `facing`.

    Valid: >= 3 distinct vertices, no repeated consecutive vertex, exactly planar, non-zero area,
    no collinear consecutive edges, and no self-intersection. Seams are allowed: an edge may be
    traversed once in each direction (a cut to a hole and back), and non-adjacent edges may touch
    at a vertex they share (the cut's end points); nothing else may touch or cross.
    """
    n = len(vs)
    assert len(set(vs)) >= 3, f"{name}: fewer than 3 distinct vertices"
    for i in range(n):
        assert vs[i] != vs[(i + 1) % n], f"{name}: repeated consecutive vertex {i}"
    normal = newell(vs)
    assert normal != (0, 0, 0), f"{name}: zero area"
    for v in vs:
        assert dot(normal, sub(v, vs[0])) == 0, f"{name}: not planar"
    assert dot(normal, facing) > 0, f"{name}: normal {normal} does not face {facing}"
    for i in range(n):  # no spike or straight-through vertex
        a, b, c = vs[i - 1], vs[i], vs[(i + 1) % n]
        assert cross(sub(b, a), sub(c, b)) != (0, 0, 0), f"{name}: collinear edges at vertex {i}"
    # Project on the plane that drops the normal's dominant axis and test every edge pair.
    k = max(range(3), key=lambda a: abs(normal[a]))
    i2, j2 = (k + 1) % 3, (k + 2) % 3
    pts = [(v[i2], v[j2]) for v in vs]
    edges = [(t, (t + 1) % n) for t in range(n)]
    for e in range(n):
        for f in range(e + 1, n):
            (a, b), (c, d) = edges[e], edges[f]
            if b == c or d == a:  # adjacent edges share exactly their common vertex (checked above)
                if (b == c and d == a) and n > 2:  # a two-edge loop: impossible for n >= 3
                    raise AssertionError(f"{name}: degenerate")
                continue
            if vs[a] == vs[d] and vs[b] == vs[c]:
                continue  # seam: the same edge, once each way
            if not segments_meet(pts[a], pts[b], pts[c], pts[d]):
                continue
            shared = {vs[a], vs[b]} & {vs[c], vs[d]}
            # Touching only at a shared end point, without overlapping, is a seam vertex: allowed.
            if len(shared) == 1:
                s = shared.pop()
                other_ab = vs[b] if vs[a] == s else vs[a]
                other_cd = vs[d] if vs[c] == s else vs[c]
                collinear_overlap = (cross(sub(other_ab, s), sub(other_cd, s)) == (0, 0, 0)
                                     and dot(sub(other_ab, s), sub(other_cd, s)) > 0)
                if not collinear_overlap:
                    continue
            raise AssertionError(f"{name}: edges {e} and {f} cross or touch")
    # Seams: without the edges traversed both ways, the boundary must fall into one outer loop
    # turning about `facing` and holes turning the opposite way.
    seam = {(vs[a], vs[b]) for a, b in edges} & {(vs[b], vs[a]) for a, b in edges}
    if seam:
        succ = {}
        for a, b in edges:
            if (vs[a], vs[b]) not in seam:
                assert vs[a] not in succ, f"{name}: ambiguous boundary at {vs[a]}"
                succ[vs[a]] = vs[b]
        signs = []
        while succ:
            start = next(iter(succ))
            loop, v = [], start
            while v in succ:
                loop.append(v)
                v = succ.pop(v)
            assert v == start, f"{name}: open boundary after removing seams"
            signs.append(dot(newell(loop), facing) > 0)
        assert signs.count(True) == 1, f"{name}: holes must turn opposite to the outer boundary"
    return abs(normal[k])


# --------------------------------------------------------------------------------------------
# Scene writer.

X_AXIS, Y_AXIS, Z_AXIS = (1, 0, 0), (0, 1, 0), (0, 0, 1)


def neg(v):
    return (-v[0], -v[1], -v[2])


class RadFile:
    def __init__(self, header):
        self.lines = [f"# {line}".rstrip() for line in header.strip().splitlines()]
        self.lines.append("# Generated by samples/generate.py; do not edit by hand.")
        self.names = set()
        self.count = 0

    def comment(self, text):
        self.lines.append("")
        self.lines.append(f"# {text}")

    def material(self, mtype, name, reals):
        self.lines.append("")
        self.lines.append(f"void {mtype} {name}")
        self.lines.append("0")
        self.lines.append("0")
        self.lines.append(f"{len(reals)} " + " ".join(reals))

    def polygon(self, modifier, name, vs, facing):
        """Writes polygon `vs` (integer mm vertices, order as given) after checking it."""
        assert name not in self.names, name
        self.names.add(name)
        check_polygon(name, vs, facing)
        self.lines.append("")
        self.lines.append(f"{modifier} polygon {name}")
        self.lines.append("0")
        self.lines.append("0")
        self.lines.append(str(3 * len(vs)))
        for v in vs:
            self.lines.append("    " + " ".join(fmt(c) for c in v))
        self.count += 1

    def rect(self, modifier, name, axis, at, u0, u1, v0, v1, facing):
        """Axis-aligned rectangle in the plane {axis = at}, spanning [u0,u1] x [v0,v1] over the
        other two axes in cyclic order (x: y,z; y: z,x; z: x,y). Vertex order is chosen so that
        the normal points along `facing` (+1 or -1 times the axis)."""
        k = "xyz".index(axis)
        iu, iv = (k + 1) % 3, (k + 2) % 3

        def pt(u, v):
            p = [0, 0, 0]
            p[k], p[iu], p[iv] = mm(at), mm(u), mm(v)
            return tuple(p)

        loop = [pt(u0, v0), pt(u1, v0), pt(u1, v1), pt(u0, v1)]  # counter-clockwise about +axis
        if facing < 0:
            loop = [loop[0]] + loop[:0:-1]
        direction = [0, 0, 0]
        direction[k] = facing
        self.polygon(modifier, name, loop, tuple(direction))

    def box(self, modifier, name, x0, x1, y0, y1, z0, z1, faces="xXyYzZ"):
        """Closed axis-aligned box, outward normals; `faces` selects x- x+ y- y+ z- z+."""
        spec = {
            "x": ("x", x0, y0, y1, z0, z1, -1), "X": ("x", x1, y0, y1, z0, z1, +1),
            "y": ("y", y0, z0, z1, x0, x1, -1), "Y": ("y", y1, z0, z1, x0, x1, +1),
            "z": ("z", z0, x0, x1, y0, y1, -1), "Z": ("z", z1, x0, x1, y0, y1, +1),
        }
        label = {"x": "west", "X": "east", "y": "south", "Y": "north", "z": "bottom", "Z": "top"}
        for f in faces:
            axis, at, u0, u1, v0, v1, facing = spec[f]
            self.rect(modifier, f"{name}_{label[f]}", axis, at, u0, u1, v0, v1, facing)

    def write(self, path):
        with open(path, "w", newline="\n") as f:
            f.write("\n".join(self.lines) + "\n")


def write_grid(path, x0, x1, y0, y1, z, step):
    """Horizontal work-plane grid, sensors facing up; all arguments in metres (decimals)."""
    x0, x1, y0, y1, z, step = (mm(v) for v in (x0, x1, y0, y1, z, step))
    xs = list(range(x0, x1 + 1, step))
    ys = list(range(y0, y1 + 1, step))
    assert xs[-1] == x1 and ys[-1] == y1, "grid bounds are not a whole number of steps apart"
    with open(path, "w", newline="\n") as f:
        for y in ys:
            for x in xs:
                f.write(f"{fmt(x)} {fmt(y)} {fmt(z)} 0 0 1\n")
    return len(xs) * len(ys)


def tile_around_holes(x0, x1, y0, y1, holes):
    """Rectangles (x0,x1,y0,y1) in metres that tile [x0,x1]x[y0,y1] minus the rectangular holes.

    Horizontal bands between the holes' y bounds; within a band, strips between the holes that
    cross it. Holes must be disjoint and inside the outer rectangle."""
    ys = sorted({y0, y1} | {h[2] for h in holes} | {h[3] for h in holes}, key=mm)
    out = []
    for ya, yb in zip(ys, ys[1:]):
        crossing = sorted((h for h in holes if mm(h[2]) <= mm(ya) and mm(yb) <= mm(h[3])),
                          key=lambda h: mm(h[0]))
        xa = x0
        for h in crossing:
            if mm(h[0]) > mm(xa):
                out.append((xa, h[0], ya, yb))
            xa = h[1]
        if mm(xa) < mm(x1):
            out.append((xa, x1, ya, yb))
    # Exact area check: tiles + holes = outer rectangle.
    area = lambda r: (mm(r[1]) - mm(r[0])) * (mm(r[3]) - mm(r[2]))
    assert sum(map(area, out)) + sum(map(area, holes)) == area((x0, x1, y0, y1))
    return out


# --------------------------------------------------------------------------------------------
# Sample 1: side-lit office.

def office(folder):
    os.makedirs(folder, exist_ok=True)
    W, D, H = "4", "6", "3"           # room interior: x 0..4, y 0..6, z 0..3
    T = "-0.3"                        # outer face of the south (window) wall
    WX0, WX1, WZ0, WZ1 = "0.8", "3.2", "0.9", "2.4"  # window opening

    s = RadFile("""
daylit sample: side-lit office, 4 m wide (x 0..4), 6 m deep (y 0..6), 3 m high (z 0..3).
Window in the south wall (y = 0 inner face, y = -0.3 outer face): x 0.8..3.2, z 0.9..2.4.
Overhang above the window outside at z 2.5..2.6, y -0.3..-1.1; an 8 m high building across the
street with its facade at y = -18; ground outside at z = 0. Metres, z up, +y north.
Normals point away from the solid each face bounds (into the room for room surfaces).
The glazing is in apertures.rad (--apertures).""")
    s.material("plastic", "floor_mat", ["0.2", "0.2", "0.2", "0", "0"])
    s.material("plastic", "wall_mat", ["0.5", "0.5", "0.5", "0", "0"])
    s.material("plastic", "ceiling_mat", ["0.8", "0.8", "0.8", "0", "0"])
    s.material("plastic", "frame_mat", ["0.4", "0.4", "0.4", "0", "0"])
    s.material("plastic", "facade_mat", ["0.35", "0.35", "0.35", "0", "0"])
    s.material("plastic", "ground_mat", ["0.15", "0.15", "0.15", "0", "0"])

    s.comment("Room: floor, ceiling and the inner faces of the west, east and north walls")
    s.rect("floor_mat", "floor", "z", 0, 0, W, 0, D, +1)
    s.rect("ceiling_mat", "ceiling", "z", H, 0, W, 0, D, -1)
    s.rect("wall_mat", "wall_west", "x", 0, 0, D, 0, H, +1)
    s.rect("wall_mat", "wall_east", "x", W, 0, D, 0, H, -1)
    s.rect("wall_mat", "wall_north", "y", D, 0, H, 0, W, -1)

    s.comment("South wall, inner face (y = 0, facing the room) with the window hole, as ONE polygon\n"
              "# with a seam: outer boundary from (0,0,0), the cut to the hole corner (0.8,0,0.9),\n"
              "# around the hole in the opposite sense, and back along the cut.")
    outer = [P(0, 0, 0), P(0, 0, H), P(W, 0, H), P(W, 0, 0)]  # clockwise in (x,z): normal +y
    hole = [P(WX0, 0, WZ0), P(WX1, 0, WZ0), P(WX1, 0, WZ1), P(WX0, 0, WZ1)]  # opposite sense
    s.polygon("wall_mat", "wall_south_inner", outer + [outer[0]] + hole + [hole[0]], Y_AXIS)

    s.comment("South wall, outer face (y = -0.3, facing south) as four rectangles around the window;\n"
              "# it runs past the room's corners by the wall thickness (x -0.3..4.3, z 0..3.3)")
    s.rect("facade_mat", "wall_south_outer_below", "y", T, 0, WZ0, "-0.3", "4.3", -1)
    s.rect("facade_mat", "wall_south_outer_above", "y", T, WZ1, "3.3", "-0.3", "4.3", -1)
    s.rect("facade_mat", "wall_south_outer_left", "y", T, WZ0, WZ1, "-0.3", WX0, -1)
    s.rect("facade_mat", "wall_south_outer_right", "y", T, WZ0, WZ1, WX1, "4.3", -1)

    s.comment("Window reveals: sill, head and jambs between y = -0.3 and y = 0, facing the opening")
    s.rect("frame_mat", "reveal_sill", "z", WZ0, WX0, WX1, T, 0, +1)
    s.rect("frame_mat", "reveal_head", "z", WZ1, WX0, WX1, T, 0, -1)
    s.rect("frame_mat", "reveal_jamb_west", "x", WX0, T, 0, WZ0, WZ1, +1)
    s.rect("frame_mat", "reveal_jamb_east", "x", WX1, T, 0, WZ0, WZ1, -1)

    s.comment("Overhang: a 0.1 m slab (z 2.5..2.6) projecting 0.8 m from the outer face, x 0.4..3.6;\n"
              "# its back (y = -0.3) is against the wall and left out")
    s.box("facade_mat", "overhang", "0.4", "3.6", "-1.1", T, "2.5", "2.6", faces="xXyzZ")

    s.comment("Obstructing building across the street: facade at y = -18 facing the office,\n"
              "# x -20..24, 8 m high, 10 m deep (y -28..-18)")
    s.box("facade_mat", "opposite", "-20", "24", "-28", "-18", "0", "8", faces="xXyYZ")

    s.comment("Ground outside the office (z = 0), x -40..44, y -40..-0.3")
    s.rect("ground_mat", "ground", "z", 0, "-40", "44", "-40", T, +1)
    s.write(os.path.join(folder, "scene.rad"))

    a = RadFile("""
daylit sample: the office window's glazing, in the plane of the wall's outer face (y = -0.3),
x 0.8..3.2, z 0.9..2.4, normal into the room. Radiance glass takes transmissivity: 0.96 gives
a normal-incidence transmittance of about 0.88.""")
    a.material("glass", "clear_glass", ["0.96", "0.96", "0.96"])
    a.comment("Window opening")
    a.rect("clear_glass", "window", "y", T, WZ0, WZ1, WX0, WX1, +1)
    a.write(os.path.join(folder, "apertures.rad"))

    n1 = write_grid(os.path.join(folder, "grid.pts"), "0.05", "3.95", "0.05", "5.95", "0.85", "0.1")
    n2 = write_grid(os.path.join(folder, "grid-dense.pts"), "0.02", "3.98", "0.02", "5.98", "0.85", "0.04")
    return s.count, a.count, n1, n2


# --------------------------------------------------------------------------------------------
# Sample 2: top-lit hall.

def hall(folder):
    os.makedirs(folder, exist_ok=True)
    L, B, H, R = "24", "12", "6", "6.4"  # x 0..24, y 0..12, roof underside z 6, top z 6.4
    KERB = "6.7"                         # top of the upstand kerbs = glazing plane
    KT = 0.15                            # kerb thickness (m)
    # Rooflights 2.4 m (x) by 1.6 m (y), centred at x 4, 12, 20 and y 3, 9.
    lights = []
    for row, cy in enumerate(("3", "9")):
        for col, cx in enumerate(("4", "12", "20")):
            x0, x1 = fmt(mm(cx) - 1200), fmt(mm(cx) + 1200)
            y0, y1 = fmt(mm(cy) - 800), fmt(mm(cy) + 800)
            lights.append((f"r{row + 1}c{col + 1}", x0, x1, y0, y1))

    s = RadFile("""
daylit sample: top-lit hall, 24 m (x 0..24) by 12 m (y 0..12), 6 m high, flat roof 0.4 m thick
(underside z = 6, top z = 6.4) with six rooflights 2.4 m x 1.6 m in two rows of three, centred
at x = 4, 12, 20 and y = 3, 9. Each opening has four reveals through the roof (z 6..6.4) and an
upstand kerb 0.15 m thick and 0.3 m high (z 6.4..6.7): inner faces flush with the opening,
outer faces, and a top. A taller building to the east: x 30..40, y -5..17, 15 m high.
Metres, z up, +y north. Normals point away from the solid each face bounds.
The rooflight openings (z = 6.7) are in apertures.rad (--apertures).""")
    s.material("plastic", "floor_mat", ["0.2", "0.2", "0.2", "0", "0"])
    s.material("plastic", "wall_mat", ["0.5", "0.5", "0.5", "0", "0"])
    s.material("plastic", "ceiling_mat", ["0.7", "0.7", "0.7", "0", "0"])
    s.material("plastic", "roof_mat", ["0.3", "0.3", "0.3", "0", "0"])
    s.material("plastic", "facade_mat", ["0.35", "0.35", "0.35", "0", "0"])

    s.comment("Hall: floor and the inner faces of the four walls")
    s.rect("floor_mat", "floor", "z", 0, 0, L, 0, B, +1)
    s.rect("wall_mat", "wall_west", "x", 0, 0, B, 0, H, +1)
    s.rect("wall_mat", "wall_east", "x", L, 0, B, 0, H, -1)
    s.rect("wall_mat", "wall_south", "y", 0, 0, H, 0, L, +1)
    s.rect("wall_mat", "wall_north", "y", B, 0, H, 0, L, -1)

    s.comment("Roof underside (z = 6, facing down), tiled by rectangles around the six openings")
    holes = [(x0, x1, y0, y1) for _, x0, x1, y0, y1 in lights]
    for i, (x0, x1, y0, y1) in enumerate(tile_around_holes("0", L, "0", B, holes)):
        s.rect("ceiling_mat", f"roof_under_{i + 1}", "z", H, x0, x1, y0, y1, -1)

    s.comment("Roof top (z = 6.4, facing up), tiled around the kerbs' outer footprints")
    kerb_out = [(fmt(mm(x0) - mm(KT)), fmt(mm(x1) + mm(KT)), fmt(mm(y0) - mm(KT)), fmt(mm(y1) + mm(KT)))
                for x0, x1, y0, y1 in holes]
    for i, (x0, x1, y0, y1) in enumerate(tile_around_holes("0", L, "0", B, kerb_out)):
        s.rect("roof_mat", f"roof_top_{i + 1}", "z", R, x0, x1, y0, y1, +1)

    for (name, x0, x1, y0, y1), (ox0, ox1, oy0, oy1) in zip(lights, kerb_out):
        s.comment(f"Rooflight {name}: opening x {x0}..{x1}, y {y0}..{y1}")
        # Reveals through the roof and the kerb's inner faces: the opening's sides, facing into it.
        for part, za, zb in (("reveal", H, R), ("kerb_in", R, KERB)):
            s.rect("roof_mat", f"{name}_{part}_w", "x", x0, y0, y1, za, zb, +1)
            s.rect("roof_mat", f"{name}_{part}_e", "x", x1, y0, y1, za, zb, -1)
            s.rect("roof_mat", f"{name}_{part}_s", "y", y0, za, zb, x0, x1, +1)
            s.rect("roof_mat", f"{name}_{part}_n", "y", y1, za, zb, x0, x1, -1)
        # Kerb outer faces, facing away from the opening.
        s.rect("roof_mat", f"{name}_kerb_out_w", "x", ox0, oy0, oy1, R, KERB, -1)
        s.rect("roof_mat", f"{name}_kerb_out_e", "x", ox1, oy0, oy1, R, KERB, +1)
        s.rect("roof_mat", f"{name}_kerb_out_s", "y", oy0, R, KERB, ox0, ox1, -1)
        s.rect("roof_mat", f"{name}_kerb_out_n", "y", oy1, R, KERB, ox0, ox1, +1)
        # Kerb top (z = 6.7): a ring of four rectangles between the opening and the outer faces.
        s.rect("roof_mat", f"{name}_kerb_top_s", "z", KERB, ox0, ox1, oy0, y0, +1)
        s.rect("roof_mat", f"{name}_kerb_top_n", "z", KERB, ox0, ox1, y1, oy1, +1)
        s.rect("roof_mat", f"{name}_kerb_top_w", "z", KERB, ox0, x0, y0, y1, +1)
        s.rect("roof_mat", f"{name}_kerb_top_e", "z", KERB, x1, ox1, y0, y1, +1)

    s.comment("Neighbouring building to the east: x 30..40, y -5..17, 15 m high")
    s.box("facade_mat", "neighbour", "30", "40", "-5", "17", "0", "15", faces="xXyYZ")
    s.write(os.path.join(folder, "scene.rad"))

    a = RadFile("""
daylit sample: the hall's six rooflight openings at the top of their kerbs (z = 6.7), as void
openings (transmittance 1), normals pointing down into the hall.""")
    for name, x0, x1, y0, y1 in lights:
        a.rect("void", f"rooflight_{name}", "z", KERB, x0, x1, y0, y1, -1)
    a.write(os.path.join(folder, "apertures.rad"))

    n = write_grid(os.path.join(folder, "grid.pts"), "0.125", "23.875", "0.125", "11.875", "0.85", "0.25")
    return s.count, a.count, n


def main():
    o = office(os.path.join(HERE, "office"))
    h = hall(os.path.join(HERE, "hall"))
    print(f"office: {o[0]} occluders, {o[1]} aperture, {o[2]} + {o[3]} sensors; "
          f"hall: {h[0]} occluders, {h[1]} apertures, {h[2]} sensors")
    return 0


if __name__ == "__main__":
    sys.exit(main())
