#!/usr/bin/env python3
"""The house's rules (DESIGN.md §1, README "Layout"), checked on every project include.

Rooms, bottom up; a file of a room may include its own room and the rooms listed as below it:

  geometry      nothing else of the project
  illumination  geometry's CGAL-free math headers (vec3, polygon, spherical_region, error)
  materials     geometry, illumination
  sky           geometry, illumination
  simulation    geometry, illumination, materials, sky
  report        the rooms above, through simulation
  bench         everything but cli
  cli           everything

and, whatever the room: illumination/ includes no CGAL, GMP, MPFR or I/O header (kernels are pure
functions of doubles), and nothing outside geometry/ includes CGAL or GMP (exact types stay in
geometry/), and MPI is cli/mpi_shards_mpi.cpp's alone (the libraries, and the default build, know nothing
of it). Tests and fuzz targets may include any room. Exits 1 and names every file:line that
breaks a rule; 0 with a one-line summary otherwise.

Usage: scripts/check_layering.py [repository root]
"""

import pathlib
import re
import sys

BELOW = {
    "geometry": set(),
    "illumination": {"geometry"},
    "materials": {"geometry", "illumination"},
    "sky": {"geometry", "illumination"},
    "simulation": {"geometry", "illumination", "materials", "sky"},
    "report": {"geometry", "illumination", "materials", "sky", "simulation"},
    "bench": {"geometry", "illumination", "materials", "sky", "simulation", "report"},
    "cli": {"geometry", "illumination", "materials", "sky", "simulation", "report", "bench"},
}
# What illumination/ may see of geometry/: plain math types, no readers, no exact visibility.
ILLUMINATION_GEOMETRY = {"geometry/vec3.hpp", "geometry/polygon.hpp", "geometry/spherical_region.hpp",
                         "geometry/error.hpp"}
# Exact arithmetic and its libraries stay in geometry/.
EXACT = re.compile(r"^(CGAL/|gmp|gmpxx|mpfr|boost/multiprecision)")
# I/O in a kernel: streams, files, C stdio, JSON, images.
IO = re.compile(r"^(iostream|fstream|sstream|istream|ostream|cstdio|stdio\.h|filesystem|nlohmann/|OpenImageIO/|fmt/)")
# MPI: the one file that distributes sensors over ranks (cli/mpi_shards.hpp), built with DAYLIT_MPI.
MPI = re.compile(r"^(mpi\.h|mpi/|mpi\.hpp$|boost/mpi)")
MPI_FILE = "cli/mpi_shards_mpi.cpp"
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    problems, checked = [], 0
    for room in BELOW:
        for path in sorted((root / room).rglob("*")):
            if path.suffix not in {".cpp", ".hpp", ".h"}:
                continue
            checked += 1
            rel = path.relative_to(root)
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                quoted, header = m.group(1) == '"', m.group(2)
                where = f"{rel}:{number}"
                if quoted and "/" in header:
                    other = header.split("/", 1)[0]
                    if other in BELOW and other != room and other not in BELOW[room]:
                        problems.append(f"{where}: {room}/ includes {header}, from {other}/, a room above it or beside it")
                    if room == "illumination" and other == "geometry" and header not in ILLUMINATION_GEOMETRY:
                        problems.append(f"{where}: illumination/ includes {header}; it may see only geometry's math "
                                        f"headers ({', '.join(sorted(ILLUMINATION_GEOMETRY))})")
                if not quoted and EXACT.match(header) and room != "geometry":
                    problems.append(f"{where}: {room}/ includes <{header}>; exact arithmetic stays in geometry/")
                if not quoted and MPI.match(header) and rel.as_posix() != MPI_FILE:
                    problems.append(f"{where}: includes <{header}>; MPI stays in {MPI_FILE}")
                if not quoted and room == "illumination" and IO.match(header):
                    problems.append(f"{where}: illumination/ includes <{header}>; kernels do no I/O")
    for p in problems:
        print(p)
    if problems:
        print(f"layering: {len(problems)} include(s) break the rules of DESIGN.md §1")
        return 1
    print(f"layering: {checked} files of {len(BELOW)} rooms follow DESIGN.md §1")
    return 0


if __name__ == "__main__":
    sys.exit(main())
