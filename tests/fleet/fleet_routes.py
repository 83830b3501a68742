"""The fleet's roads: each a shipped route file per direction, or one direction and its reverse.

A road driven both ways is two lanes. The shipped county road has a route file per lane; the
Mainline and the synthetic highway ship one direction, so the other is made here: the points in
reverse order, each cell mirrored along the polyline (start' = length - end). A cell keeps its id
in both directions, as the county road's lanes do; the direction tells the lanes apart
(truth/sections.csv). Each lane is its own pavement in the simulator (its own road_seed, so its
own roughness) with the same CRR as the other lane's cell of that id.
"""
import math
import shutil
import tomllib
from dataclasses import dataclass

# WGS84
A_M = 6378137.0
F = 1 / 298.257223563
E2 = F * (2 - F)


def segment_m(p, q):
    """Distance between two route points on the ellipsoid. The points of the routes used are at
    most 500 m apart, where the local radii of curvature at the midpoint give the geodesic to
    1e-8 of its length (the simulator's GeographicLib and this agree to millimetres on 110 km)."""
    lat = math.radians((p["lat_deg"] + q["lat_deg"]) / 2)
    w = 1 - E2 * math.sin(lat) ** 2
    meridian = A_M * (1 - E2) / w ** 1.5
    normal = A_M / math.sqrt(w)
    dn = meridian * math.radians(q["lat_deg"] - p["lat_deg"])
    de = normal * math.cos(lat) * math.radians(q["lon_deg"] - p["lon_deg"])
    return math.hypot(dn, de)


def polyline_m(points):
    return sum(segment_m(p, q) for p, q in zip(points, points[1:]))


@dataclass
class Lane:
    road: str        # the road's short name (county, mainline, highway)
    direction: str   # eastbound, westbound
    file: str        # the route file, relative to the fleet folder
    start_m: float   # the drives' sub-range along this lane's route
    end_m: float
    road_seed: int   # the lane's roughness and joints: the same for every drive on it
    cells: list      # the route's cells driven whole: dicts of the route file's keys


@dataclass
class Road:
    name: str
    forward: str            # shipped route file (config/routes) of the forward direction
    forward_direction: str
    backward: str           # shipped route file of the other direction, or "" to reverse forward
    backward_direction: str
    backward_name: str      # the reversed route's name (unused with a shipped backward file)
    start_m: float          # the forward lane's sub-range: a few km, the cells inside it driven whole
    end_m: float
    speeds_mph: tuple       # slow, fast: each truck drives the road at one of them
    faulting_m: float       # the concrete's joint faulting (effect joint-faulting), the road's own


# Sub-ranges of the forward lane; the other lane drives the same cells. Each starts RUN_IN_M before
# its first cell, for the filter to settle, and ends RUN_OUT_M after the last, so the last axle
# leaves it.
RUN_IN_M = 300.0
RUN_OUT_M = 60.0
ROADS = [
    Road("county", "example-county-road-eastbound.toml", "eastbound", "example-county-road-westbound.toml", "westbound", "",
         900.0, 3660.0, (40, 55), 0.002),
    Road("mainline", "mnroad-mainline-westbound.toml", "westbound", "", "eastbound",
         "MnROAD Mainline, eastbound: the westbound lane's cells driven the other way", 1670.0, 4460.0, (45, 62), 0.0033),
    Road("highway", "synthetic-highway.toml", "westbound", "", "eastbound", "Synthetic highway, eastbound",
         1700.0, 4060.0, (50, 65), 0.0005),
]


def toml_scalar(v):
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return repr(v)


def route_text(doc, comment):
    """A route file from its parsed keys (points and cells as [[point]] and [[cell]] tables)."""
    lines = ["# " + line for line in comment.splitlines()]
    lines += [f"{k} = {toml_scalar(v)}" for k, v in doc.items() if not isinstance(v, list)]
    for key in ("point", "cell"):
        for item in doc.get(key, []):
            lines += ["", f"[[{key}]]"] + [f"{k} = {toml_scalar(v)}" for k, v in item.items()]
    return "\n".join(lines) + "\n"


def reversed_route(doc, name):
    """The route driven the other way: the points reversed, each cell mirrored."""
    if "geometry" in doc or "grade" in doc:
        raise SystemExit(f"{doc['name']}: reversing a route with a geometry or grade file is not supported")
    points = list(reversed(doc["point"]))
    length = polyline_m(doc["point"])
    cells = []
    for c in reversed(doc.get("cell", [])):
        start = round(length - (c["start_m"] + c["length_m"]), 3)
        end = round(length - c["start_m"], 3)
        if cells and start < cells[-1]["start_m"] + cells[-1]["length_m"]:
            start = cells[-1]["start_m"] + cells[-1]["length_m"]  # abutting cells stay abutting after rounding
        cells.append({**c, "start_m": start, "length_m": round(end - start, 3)})
    out = {k: v for k, v in doc.items() if k not in ("point", "cell")}
    out["name"] = name
    out["source"] = f"{doc.get('source', '')}; reversed by tests/fleet/fleet_routes.py"
    out["point"] = points
    out["cell"] = cells
    return out


def driven_cells(doc, start_m, end_m):
    """The cells a drive from start_m to end_m covers whole, with its run-in and run-out."""
    return [c for c in doc.get("cell", [])
            if c["start_m"] >= start_m + RUN_IN_M - 1e-6 and c["start_m"] + c["length_m"] <= end_m - RUN_OUT_M + 1e-6]


def covering(doc, ids):
    """The sub-range that drives the cells named ids whole, with run-in and run-out."""
    cells = [c for c in doc.get("cell", []) if c["id"] in ids]
    if {c["id"] for c in cells} != set(ids):
        raise SystemExit(f"{doc['name']}: no cell {sorted(set(ids) - {c['id'] for c in cells})}")
    start = min(c["start_m"] for c in cells) - RUN_IN_M
    end = max(c["start_m"] + c["length_m"] for c in cells) + RUN_OUT_M
    return math.floor(start * 10) / 10, math.ceil(end * 10) / 10


def copy_route(config, routes, file):
    """A shipped route file (and its geometry file) into the fleet's folder; its parsed keys."""
    doc = tomllib.loads((config / "routes" / file).read_text())
    shutil.copy(config / "routes" / file, routes / file)
    if "geometry" in doc:
        shutil.copy(config / "routes" / doc["geometry"], routes / doc["geometry"])
    return doc


def make_lanes(config, out, seed):
    """Copies or writes each road's two route files into out/routes; returns the lanes. The
    other direction's sub-range mirrors the forward one, so both lanes cover the same cells."""
    routes = out / "routes"
    routes.mkdir(parents=True, exist_ok=True)
    lanes = []
    for r, road in enumerate(ROADS):
        forward = copy_route(config, routes, road.forward)
        cells = driven_cells(forward, road.start_m, road.end_m)
        lanes.append(Lane(road.name, road.forward_direction, f"routes/{road.forward}", road.start_m, road.end_m,
                          seed * 1000 + 2 * r, cells))
        if road.backward:
            file = road.backward
            back = copy_route(config, routes, file)
        else:
            back = reversed_route(forward, road.backward_name)
            file = road.forward.replace(road.forward_direction, road.backward_direction)
            if file == road.forward:
                file = road.forward.replace(".toml", f"-{road.backward_direction}.toml")
            comment = (f"The {road.forward_direction} route {road.forward} driven the other way, for the fleet\n"
                       "(tests/fleet/make_fleet.py): points reversed, each cell mirrored along the polyline,\n"
                       "the same cell ids, CRR, roughness and joints.")
            (routes / file).write_text(route_text(back, comment))
        start, end = covering(back, [c["id"] for c in cells])
        lanes.append(Lane(road.name, road.backward_direction, f"routes/{file}", start, end, seed * 1000 + 2 * r + 1,
                          driven_cells(back, start, end)))
    return lanes
