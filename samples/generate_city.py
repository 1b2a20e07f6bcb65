#!/usr/bin/env python3
"""Generates daylit's city sample (samples/city): a first-floor room in a city block, its site file
and a GeoJSON of the neighbouring buildings.

Standard library only and deterministic; it reuses the writers and exact polygon checks of
samples/generate.py. The room is modelled in metres (z up) in scene.rad and apertures.rad; the
neighbours are footprints in WGS84 longitude/latitude (buildings.geojson) with a "height"
property, as an OpenStreetMap export gives them, which daylit places with the site (site.json).

The site is real, the footprints are not: the origin is at about 41.3925 N, 2.1640 E in Barcelona's
Eixample, whose street grid is turned 45 degrees from true north, and the blocks follow Cerda's
plan (113.3 m blocks with chamfered corners and courtyards, 20 m streets), but their outlines and
heights are invented. Plan coordinates are turned into longitude/latitude here with the local
first-order formulas (meridian and prime-vertical radii of curvature at the origin), good to a
few millimetres within 300 m; daylit itself places them with GeographicLib.
"""

import json
import math
import os
import sys

import generate as g

HERE = os.path.dirname(os.path.abspath(__file__))

# Site: the model's origin and the turn of its axes. +x runs along the street (bearing 45 deg,
# towards the north-east), +y into the block (bearing 315 deg): true north lies 45 deg clockwise
# from +y, seen from above.
LATITUDE, LONGITUDE, ELEVATION, NORTH_DEG = 41.3925, 2.164, 95.0, 45.0

# Blocks of Cerda's grid in plan metres: the room's block spans x -40..73.3, its street facade at
# y = -0.3 (the outer face of the room's window wall); blocks repeat every 133.3 m (113.3 m block,
# 20 m street).
BLOCK, PITCH, CHAMFER, DEPTH = 113.3, 133.3, 15.0, 25.0


def block_outline(i, j, setback=0.0):
    """Chamfered square outline (anticlockwise) of block (i, j); its low-y side is at
    y = -0.3 + PITCH*j + setback."""
    x0, y0 = -40.0 + PITCH * i, -0.3 + PITCH * j + setback
    x1, y1 = x0 + BLOCK, -0.3 + PITCH * j + BLOCK
    return chamfered(x0, x1, y0, y1, CHAMFER)


def courtyard(i, j):
    """Courtyard hole of block (i, j), DEPTH metres inside the outline (clockwise)."""
    x0, y0 = -40.0 + PITCH * i + DEPTH, -0.3 + PITCH * j + DEPTH
    x1, y1 = -40.0 + PITCH * i + BLOCK - DEPTH, -0.3 + PITCH * j + BLOCK - DEPTH
    return list(reversed(chamfered(x0, x1, y0, y1, CHAMFER / 2)))


def chamfered(x0, x1, y0, y1, c):
    return [(x0 + c, y0), (x1 - c, y0), (x1, y0 + c), (x1, y1 - c), (x1 - c, y1), (x0 + c, y1), (x0, y1 - c), (x0, y0 + c)]


def rectangle(x0, x1, y0, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


# --------------------------------------------------------------------------------------------
# Plan metres to WGS84 (first order about the origin; see the module comment).

A, F = 6378137.0, 1 / 298.257223563
E2 = F * (2 - F)


def lonlat(x, y):
    n = math.radians(NORTH_DEG)
    east = x * math.cos(n) - y * math.sin(n)
    north = x * math.sin(n) + y * math.cos(n)
    phi = math.radians(LATITUDE)
    w = math.sqrt(1 - E2 * math.sin(phi) ** 2)
    meridian = A * (1 - E2) / w ** 3 + ELEVATION
    prime = A / w + ELEVATION
    lat = LATITUDE + math.degrees(north / meridian)
    lon = LONGITUDE + math.degrees(east / (prime * math.cos(phi)))
    return [round(lon, 7), round(lat, 7)]  # 1e-7 degrees: about 1 cm, OpenStreetMap's precision


def check_rings(name, rings):
    """Exact checks (integer millimetres) of an outline and its holes, as generate.py does for
    polygons: simple rings, outline anticlockwise, holes clockwise and inside it."""
    mm_rings = [[(g.mm(round(x, 3)), g.mm(round(y, 3)), 0) for x, y in ring] for ring in rings]
    g.check_polygon(f"{name} outline", mm_rings[0], (0, 0, 1))
    for k, hole in enumerate(mm_rings[1:]):
        g.check_polygon(f"{name} hole {k + 1}", hole, (0, 0, -1))
        xs, ys = [p[0] for p in mm_rings[0]], [p[1] for p in mm_rings[0]]
        assert all(min(xs) < p[0] < max(xs) and min(ys) < p[1] < max(ys) for p in hole), f"{name}: hole outside"


def polygon_coordinates(name, rings):
    check_rings(name, rings)
    return [[lonlat(x, y) for x, y in ring + [ring[0]]] for ring in rings]


def feature(osm_id, geometry, properties):
    return {"type": "Feature", "id": osm_id, "properties": properties, "geometry": geometry}


def buildings():
    features = []

    def polygon(osm_id, name, rings, **props):
        props = {"building": "yes", "name": name, **props}
        features.append(feature(osm_id, {"type": "Polygon", "coordinates": polygon_coordinates(name, rings)}, props))

    # The room's own block: an OpenStreetMap export has it; daylit leaves it out (it holds the room).
    polygon("way/1000", "own block (holds the room)", [block_outline(0, 0), courtyard(0, 0)], height="22")
    # Across the street: the block the window looks at, with its courtyard, and a low workshop in
    # that courtyard (below the room's work plane: left out).
    polygon("way/1001", "block across the street", [block_outline(0, -1), courtyard(0, -1)], height="21 m")
    polygon("way/1002", "courtyard workshop", [rectangle(-2.0, 30.0, -95.0, -65.0)], height=4)
    # Diagonally across the crossings.
    polygon("way/1003", "block south-west", [block_outline(-1, -1), courtyard(-1, -1)], height=18)
    # The south-east block as two buildings, each a U around half of the courtyard, split by two
    # passages 6 m wide: one MultiPolygon feature.
    x0, y0 = -40.0 + PITCH, -0.3 - PITCH
    xm = x0 + BLOCK / 2
    west = [(x0 + CHAMFER, y0), (xm - 3, y0), (xm - 3, y0 + DEPTH), (x0 + DEPTH, y0 + DEPTH),
            (x0 + DEPTH, y0 + BLOCK - DEPTH), (xm - 3, y0 + BLOCK - DEPTH), (xm - 3, y0 + BLOCK),
            (x0 + CHAMFER, y0 + BLOCK), (x0, y0 + BLOCK - CHAMFER), (x0, y0 + CHAMFER)]
    east = [(2 * xm - x, y) for x, y in reversed(west)]  # mirrored about x = xm, kept anticlockwise
    features.append(feature("relation/2001", {"type": "MultiPolygon", "coordinates": [
        polygon_coordinates("south-east block, west part", [west]),
        polygon_coordinates("south-east block, east part", [east])]},
        {"building": "yes", "name": "block south-east (two buildings)", "height": 24}))
    # A tower two blocks away across the street (hidden by the block in between, but placed).
    polygon("way/1004", "tower two blocks away", [rectangle(10.0, 30.0, -190.0, -170.0)], height=30)
    # The blocks beside and behind the room's own, their facades 0.5 m behind the window's plane:
    # nothing there can be seen through the window (left out, exactly).
    polygon("way/1005", "block west", [block_outline(-1, 0, 0.8), courtyard(-1, 0)], height=20)
    polygon("way/1006", "block east", [block_outline(1, 0, 0.8), courtyard(1, 0)], height=20)
    polygon("way/1007", "block behind", [block_outline(0, 1), courtyard(0, 1)], height=16)
    # Two small towers 6 km away, in front of the window: too small to matter (left out, with a
    # bound on what that changes).
    polygon("way/1008", "small tower 6 km south", [rectangle(-3000.0, -2997.0, -5200.0, -5197.0)], height=8)
    polygon("way/1009", "small tower 6 km south-east", [rectangle(2500.0, 2503.0, -5500.0, -5497.0)], height=8)
    # An entrance node, as exports have them: not a footprint, skipped with a notice.
    features.append(feature("node/3001", {"type": "Point", "coordinates": lonlat(2.5, -0.3)}, {"entrance": "main"}))
    return {"type": "FeatureCollection", "features": features}


# --------------------------------------------------------------------------------------------
# The room.

def room(folder):
    W, D, Z0, Z1 = "5", "6", "4", "7"  # interior x 0..5, y 0..6, floor z 4, ceiling z 7
    T = "-0.3"                         # outer face of the window wall
    WX0, WX1, WZ0, WZ1 = "1", "4", "4.9", "6.6"

    s = g.RadFile("""
daylit sample: a first-floor room in a city block (samples/city), interior 5 m wide (x 0..5),
6 m deep (y 0..6), floor z = 4, ceiling z = 7. Window in the street wall (inner face y = 0, outer
face y = -0.3): x 1..4, z 4.9..6.6. The neighbouring buildings are in buildings.geojson, placed
by site.json (--site, --context). Metres, z up; +y points 45 degrees west of true north.
The glazing is in apertures.rad (--apertures).""")
    s.material("plastic", "floor_mat", ["0.2", "0.2", "0.2", "0", "0"])
    s.material("plastic", "wall_mat", ["0.5", "0.5", "0.5", "0", "0"])
    s.material("plastic", "ceiling_mat", ["0.8", "0.8", "0.8", "0", "0"])
    s.material("plastic", "frame_mat", ["0.4", "0.4", "0.4", "0", "0"])
    s.material("plastic", "facade_mat", ["0.35", "0.35", "0.35", "0", "0"])

    s.comment("Room: floor, ceiling and the inner faces of the side and back walls")
    s.rect("floor_mat", "floor", "z", Z0, 0, W, 0, D, +1)
    s.rect("ceiling_mat", "ceiling", "z", Z1, 0, W, 0, D, -1)
    s.rect("wall_mat", "wall_west", "x", 0, 0, D, Z0, Z1, +1)
    s.rect("wall_mat", "wall_east", "x", W, 0, D, Z0, Z1, -1)
    s.rect("wall_mat", "wall_back", "y", D, Z0, Z1, 0, W, -1)

    s.comment("Window wall, inner face (y = 0) with the window hole: one polygon with a seam")
    outer = [g.P(0, 0, Z0), g.P(0, 0, Z1), g.P(W, 0, Z1), g.P(W, 0, Z0)]
    hole = [g.P(WX0, 0, WZ0), g.P(WX1, 0, WZ0), g.P(WX1, 0, WZ1), g.P(WX0, 0, WZ1)]
    s.polygon("wall_mat", "wall_street_inner", outer + [outer[0]] + hole + [hole[0]], g.Y_AXIS)

    s.comment("Window wall, outer face (y = -0.3) around the window: the facade between the floors")
    s.rect("facade_mat", "facade_below", "y", T, Z0, WZ0, "-0.3", "5.3", -1)
    s.rect("facade_mat", "facade_above", "y", T, WZ1, "7.3", "-0.3", "5.3", -1)
    s.rect("facade_mat", "facade_left", "y", T, WZ0, WZ1, "-0.3", WX0, -1)
    s.rect("facade_mat", "facade_right", "y", T, WZ0, WZ1, WX1, "5.3", -1)

    s.comment("Window reveals between y = -0.3 and y = 0")
    s.rect("frame_mat", "reveal_sill", "z", WZ0, WX0, WX1, T, 0, +1)
    s.rect("frame_mat", "reveal_head", "z", WZ1, WX0, WX1, T, 0, -1)
    s.rect("frame_mat", "reveal_jamb_west", "x", WX0, T, 0, WZ0, WZ1, +1)
    s.rect("frame_mat", "reveal_jamb_east", "x", WX1, T, 0, WZ0, WZ1, -1)

    s.comment("A balcony slab under the window of the floor above (z 7.3..7.45), 0.9 m deep")
    s.box("facade_mat", "balcony", "0.5", "4.5", "-1.2", T, "7.3", "7.45", faces="xXyzZ")
    s.write(os.path.join(folder, "scene.rad"))

    a = g.RadFile("""
daylit sample (samples/city): the room's glazing in the plane of the facade (y = -0.3), x 1..4,
z 4.9..6.6, normal into the room; Radiance glass of transmissivity 0.96 (0.88 at normal incidence).""")
    a.material("glass", "clear_glass", ["0.96", "0.96", "0.96"])
    a.rect("clear_glass", "window", "y", T, WZ0, WZ1, WX0, WX1, +1)
    a.write(os.path.join(folder, "apertures.rad"))

    n = g.write_grid(os.path.join(folder, "grid.pts"), "0.25", "4.75", "0.25", "5.75", "4.85", "0.25")
    return s.count, a.count, n


def main():
    folder = os.path.join(HERE, "city")
    os.makedirs(folder, exist_ok=True)
    occluders, apertures, sensors = room(folder)
    site = {
        "name": "daylit sample: a first-floor room in Barcelona's Eixample",
        "comment": "elevation_m is ellipsoidal (WGS84): about 45 m above sea level plus the geoid's 50 m; "
                   "true north lies 45 degrees clockwise from the model's +y axis",
        "latitude_deg": LATITUDE, "longitude_deg": LONGITUDE, "elevation_m": ELEVATION, "north_deg": NORTH_DEG,
    }
    with open(os.path.join(folder, "site.json"), "w", newline="\n") as f:
        json.dump(site, f, indent=2)
        f.write("\n")
    collection = buildings()
    with open(os.path.join(folder, "buildings.geojson"), "w", newline="\n") as f:
        f.write('{"type": "FeatureCollection", "features": [\n')
        f.write(",\n".join(json.dumps(feat, separators=(", ", ": ")) for feat in collection["features"]))
        f.write("\n]}\n")
    print(f"city: {occluders} occluders, {apertures} aperture, {sensors} sensors, "
          f"{len(collection['features'])} features in buildings.geojson")
    return 0


if __name__ == "__main__":
    sys.exit(main())
