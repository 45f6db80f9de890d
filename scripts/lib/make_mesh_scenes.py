#!/usr/bin/env python3
"""make_mesh_scenes.py [--wavelengths-per-beam K] OUTDIR: writes mesh scenes.

  sphere_mesh.json + sphere_mesh.obj
      The optics bench's mesh scene, opticsMeshScene(1'000'000) of
      host/bench/optics_bench.cpp: tessellatedSphere({0, 0, 1}, 0.3, 1e6)
      (the same vertices in the same order, the same triangles and winding,
      each coordinate written as the repr of the double the bench computes),
      grey (diffuse 0.5), lit by a 10 W spot at 550 nm (a line) whose cone
      of half angle 17.5 degrees just covers it, seen through a pinhole
      (0.04 m, radius 1 mm) on a bare 24 x 24 mm, 128 x 128 sensor at the
      origin looking along +z; the default spectrum (360-830 nm, 94 bins);
      1e6 beams.
      The bench carries one wavelength a beam. render.wavelengths_per_beam
      is written only with --wavelengths-per-beam K (revisions before
      3a3b0c3, e500837 among them, refuse the key; their beams carry one).
  room.json + room_*.obj
      A room seen from inside (floor, walls and ceiling), a table with a
      bowl, a ball and a vase on it, two chairs (one OBJ placed twice), a
      sofa, a shelf with balls, a floor vase: over 200,000 triangles in
      diffuse greys, lit by two spots under the ceiling (points: never
      seen directly, so no emitter in the image),
      through a pinhole.

Prints one line per scene written: its name and its triangles.
Python 3 standard library only.
"""
import json
import math
import os
import sys

# --------------------------------------------------------------------------
# Meshes: a list of vertices (x, y, z) and triangles (0-based indices),
# counter-clockwise seen from outside (normal out).


class Mesh:
    def __init__(self):
        self.v = []
        self.f = []

    def add_vertex(self, p):
        self.v.append(p)
        return len(self.v) - 1

    def extend(self, other):
        base = len(self.v)
        self.v.extend(other.v)
        self.f.extend((a + base, b + base, c + base) for a, b, c in other.f)
        return self

    def flipped(self):
        m = Mesh()
        m.v = list(self.v)
        m.f = [(a, c, b) for a, b, c in self.f]
        return m

    def translated(self, t):
        m = Mesh()
        m.v = [(x + t[0], y + t[1], z + t[2]) for x, y, z in self.v]
        m.f = list(self.f)
        return m


def write_obj(path, mesh, comment, fmt):
    """fmt: a function from a float to its text."""
    lines = ["# " + line for line in comment.splitlines()]
    lines.extend("v %s %s %s" % (fmt(x), fmt(y), fmt(z)) for x, y, z in mesh.v)
    lines.extend("f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in mesh.f)
    with open(path, "w") as out:
        out.write("\n".join(lines))
        out.write("\n")


def short(x):
    """Compact text for the room's meshes (7 significant digits)."""
    s = "%.7g" % x
    return "0" if s in ("-0", "0") else s


def grid(origin, u, v, nu, nv):
    """A parallelogram origin + s u + t v, s, t in [0, 1], as nu x nv quads;
    its normal is u x v."""
    m = Mesh()
    for j in range(nv + 1):
        for i in range(nu + 1):
            s, t = i / nu, j / nv
            m.v.append(tuple(origin[k] + s * u[k] + t * v[k] for k in range(3)))
    row = nu + 1
    for j in range(nv):
        for i in range(nu):
            a = j * row + i
            b, c, d = a + 1, a + row + 1, a + row
            m.f.append((a, b, c))
            m.f.append((a, c, d))
    return m


def box(lo, hi, n=1):
    """An axis-aligned box, each face n x n quads (faces do not share their
    edge vertices: fine for diffuse surfaces, which need no closed mesh)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    faces = [
        ((x1, y0, z0), (0, dy, 0), (0, 0, dz)),   # +x
        ((x0, y0, z0), (0, 0, dz), (0, dy, 0)),   # -x
        ((x0, y1, z0), (0, 0, dz), (dx, 0, 0)),   # +y
        ((x0, y0, z0), (dx, 0, 0), (0, 0, dz)),   # -y
        ((x0, y0, z1), (dx, 0, 0), (0, dy, 0)),   # +z
        ((x0, y0, z0), (0, dy, 0), (dx, 0, 0)),   # -z
    ]
    m = Mesh()
    for o, u, v in faces:
        m.extend(grid(o, u, v, n, n))
    return m


def lathe(profile, segments, bottom_pole=None, top_pole=None, centre=(0.0, 0.0, 0.0)):
    """Revolves profile [(r, y), ...] (r > 0, from bottom to top) about the
    vertical axis through centre; bottom_pole / top_pole: the y of a point
    on the axis that closes that end, or None (open). Closed and outward
    when both poles are given."""
    cx, cy, cz = centre
    m = Mesh()
    rings = len(profile)
    for r, y in profile:
        for s in range(segments):
            phi = 2.0 * math.pi * s / segments
            m.v.append((cx + r * math.cos(phi), cy + y, cz + r * math.sin(phi)))

    def at(i, s):
        return i * segments + s % segments

    for i in range(rings - 1):
        for s in range(segments):
            m.f.append((at(i, s), at(i + 1, s), at(i + 1, s + 1)))
            m.f.append((at(i, s), at(i + 1, s + 1), at(i, s + 1)))
    if bottom_pole is not None:
        p = m.add_vertex((cx, cy + bottom_pole, cz))
        m.f.extend((p, at(0, s), at(0, s + 1)) for s in range(segments))
    if top_pole is not None:
        p = m.add_vertex((cx, cy + top_pole, cz))
        m.f.extend((p, at(rings - 1, s + 1), at(rings - 1, s)) for s in range(segments))
    return m


def cylinder(radius, y0, y1, segments, centre=(0.0, 0.0, 0.0), rings=1):
    profile = [(radius, y0 + (y1 - y0) * i / rings) for i in range(rings + 1)]
    return lathe(profile, segments, y0, y1, centre)


def ball(radius, rings, centre):
    """A sphere as a lathe: rings bands, 2 x rings segments."""
    profile = [(radius * math.sin(math.pi * i / rings), -radius * math.cos(math.pi * i / rings))
               for i in range(1, rings)]
    return lathe(profile, 2 * rings, -radius, radius, centre)


def vase(height, radius, bands, segments, centre):
    """A closed vase-like solid of revolution (its mouth closed by a lid)."""
    profile = []
    for i in range(bands + 1):
        t = i / bands
        r = radius * (0.55 + 0.45 * math.sin(math.pi * (0.15 + 1.1 * t)) + 0.12 * math.sin(6.0 * math.pi * t))
        profile.append((max(r, 0.2 * radius), height * t))
    return lathe(profile, segments, 0.0, height, centre)


# --------------------------------------------------------------------------
# The bench's sphere: tessellatedSphere in host/bench/optics_bench.cpp.


def tessellated_sphere(centre, radius, triangles):
    rings = max(3, int(math.floor(math.sqrt(triangles / 4.0) + 0.5)))  # std::lround, x >= 0
    segments = 2 * rings
    cx, cy, cz = centre
    m = Mesh()
    m.v.append((cx + 0.0, cy + 0.0, cz + radius))  # north pole
    for r in range(1, rings):
        theta = math.pi * float(r) / float(rings)
        st, ct = math.sin(theta), math.cos(theta)
        for s in range(segments):
            phi = 2.0 * math.pi * float(s) / float(segments)
            # centre + radius * dvec3(sin t cos p, sin t sin p, cos t)
            m.v.append((cx + radius * (st * math.cos(phi)), cy + radius * (st * math.sin(phi)), cz + radius * ct))
    south = len(m.v)
    m.v.append((cx - 0.0, cy - 0.0, cz - radius))

    def ring_vertex(r, s):
        return 1 + (r - 1) * segments + s % segments

    for s in range(segments):
        m.f.append((0, ring_vertex(1, s), ring_vertex(1, s + 1)))
    for r in range(1, rings - 1):
        for s in range(segments):
            m.f.append((ring_vertex(r, s), ring_vertex(r + 1, s), ring_vertex(r + 1, s + 1)))
            m.f.append((ring_vertex(r, s), ring_vertex(r + 1, s + 1), ring_vertex(r, s + 1)))
    for s in range(segments):
        m.f.append((ring_vertex(rings - 1, s), south, ring_vertex(rings - 1, s + 1)))
    return m


def normalize(v):
    # glm::normalize: v * inversesqrt(dot(v, v)).
    inv = 1.0 / math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return [v[0] * inv, v[1] * inv, v[2] * inv]


def write_json(path, scene):
    with open(path, "w") as out:
        json.dump(scene, out, indent=2)
        out.write("\n")


def sphere_mesh_scene(outdir, wavelengths_per_beam):
    mesh = tessellated_sphere((0.0, 0.0, 1.0), 0.3, 1000000)
    write_obj(os.path.join(outdir, "sphere_mesh.obj"), mesh,
              "tessellatedSphere({0, 0, 1}, 0.3, 1'000'000) of host/bench/optics_bench.cpp\n"
              "(the optics bench's mesh scene), written by scripts/lib/make_mesh_scenes.py.\n"
              "Faces counter-clockwise seen from outside.", repr)
    render = {"beams": 1000000, "seed": 1}
    if wavelengths_per_beam is not None:
        render["wavelengths_per_beam"] = wavelengths_per_beam
    scene = {
        "spectrum": {"min_nm": 360, "max_nm": 830, "bins": 94},
        "camera": {
            "position": [0, 0, 0],
            "look_at": [0, 0, 1],
            "up": [0, 1, 0],
            "sensor": {"width_m": 0.024, "height_m": 0.024, "pixels": [128, 128]},
            "pinhole": {"distance_m": 0.04, "radius_m": 0.001},
        },
        "lights": [{
            "name": "550 nm",
            "type": "spot",
            "position": [0.6, 0.6, 0.4],
            "direction": normalize([-0.6, -0.6, 0.6]),
            "cone_deg": 17.5,
            "power_w": 10,
            "spd": {"line_nm": 550},
        }],
        "objects": [{
            "name": "tessellated sphere",
            "type": "mesh",
            "file": "sphere_mesh.obj",
            "material": {"type": "diffuse", "reflectance": 0.5},
        }],
        "render": render,
    }
    write_json(os.path.join(outdir, "sphere_mesh.json"), scene)
    return len(mesh.f)


# --------------------------------------------------------------------------
# The room: x across (-3..3), y up (floor 0, ceiling 2.8), z away from the
# camera (back wall at 5.5, the wall behind the camera at -0.5).

ROOM_LO = (-3.0, 0.0, -0.5)
ROOM_HI = (3.0, 2.8, 5.5)


def chair():
    """A chair at the origin, its seat facing +z, its back towards -z."""
    m = Mesh()
    m.extend(box((-0.23, 0.43, -0.23), (0.23, 0.47, 0.23), 12))           # seat
    m.extend(box((-0.23, 0.47, -0.23), (0.23, 0.95, -0.19), 12))          # back
    for x in (-0.2, 0.2):
        for z in (-0.2, 0.2):
            m.extend(cylinder(0.02, 0.0, 0.43, 32, (x, 0.0, z), rings=4))
    return m


def room_scene(outdir):
    files = []  # (object entry, triangles)

    def add(name, mesh, reflectance, transform=None, file=None, comment=""):
        file = file or "room_%s.obj" % name
        path = os.path.join(outdir, file)
        if not os.path.exists(path) or file == "room_%s.obj" % name:
            write_obj(path, mesh, "%s, written by scripts/lib/make_mesh_scenes.py.%s" % (name, comment), short)
        entry = {"name": name, "type": "mesh", "file": file,
                 "material": {"type": "diffuse", "reflectance": reflectance}}
        if transform:
            entry["transform"] = transform
        files.append((entry, len(mesh.f)))

    # Shell seen from inside: faces turned inwards.
    (x0, y0, z0), (x1, y1, z1) = ROOM_LO, ROOM_HI
    floor = grid((x0, y0, z0), (0, 0, z1 - z0), (x1 - x0, 0, 0), 12, 12)  # normal +y
    add("floor", floor, 0.35)
    walls = box(ROOM_LO, ROOM_HI, 12).flipped()
    walls.f = [t for t in walls.f if not all(walls.v[i][1] == y0 for i in t)]  # the floor is apart
    add("shell", walls, 0.75, comment="\nWalls and ceiling, faces towards the inside.")

    # Table at (0, 0, 3).
    table = Mesh()
    table.extend(box((-0.8, 0.72, 2.55), (0.8, 0.76, 3.45), 30))
    for x in (-0.72, 0.72):
        for z in (2.63, 3.37):
            table.extend(cylinder(0.035, 0.0, 0.72, 48, (x, 0.0, z), rings=8))
    add("table", table, 0.45)
    # On the table: a vase, a ball, a bowl (a squat vase).
    add("table_vase", vase(0.35, 0.08, 150, 200, (-0.45, 0.76, 3.0)), 0.8)
    add("table_ball", ball(0.12, 120, (0.35, 0.88, 2.95)), 0.6)
    add("bowl", vase(0.08, 0.14, 40, 160, (0.0, 0.76, 3.25)), 0.9)

    # Two chairs, one OBJ.
    c = chair()
    write_obj(os.path.join(outdir, "room_chair.obj"), c,
              "chair (its seat facing +z), written by scripts/lib/make_mesh_scenes.py.", short)
    add("chair_left", c, 0.3, {"rotate_deg": [0, 90, 0], "translate": [-1.15, 0, 3.0]}, "room_chair.obj")
    add("chair_right", c, 0.3, {"rotate_deg": [0, -90, 0], "translate": [1.15, 0, 3.0]}, "room_chair.obj")

    # Sofa against the back wall.
    sofa = Mesh()
    sofa.extend(box((-1.1, 0.1, 4.6), (1.1, 0.45, 5.45), 16))    # seat
    sofa.extend(box((-1.1, 0.45, 5.2), (1.1, 0.95, 5.45), 16))   # back
    sofa.extend(box((-1.3, 0.1, 4.6), (-1.1, 0.65, 5.45), 16))   # arms
    sofa.extend(box((1.1, 0.1, 4.6), (1.3, 0.65, 5.45), 16))
    for x in (-1.25, 1.25):
        for z in (4.65, 5.4):
            sofa.extend(cylinder(0.03, 0.0, 0.1, 24, (x, 0.0, z)))
    add("sofa", sofa, 0.55)

    # Shelf along the left wall, with balls.
    shelf = Mesh()
    shelf.extend(box((-2.95, 0.0, 2.6), (-2.6, 1.9, 2.63), 10))  # sides
    shelf.extend(box((-2.95, 0.0, 4.37), (-2.6, 1.9, 4.4), 10))
    for y in (0.05, 0.5, 0.95, 1.4, 1.87):
        shelf.extend(box((-2.95, y, 2.63), (-2.6, y + 0.03, 4.37), 10))
    add("shelf", shelf, 0.65)
    balls = Mesh()
    for i, (y, z, r) in enumerate([(0.53, 3.0, 0.1), (0.98, 3.5, 0.12), (1.43, 4.0, 0.09), (0.08, 3.8, 0.12)]):
        balls.extend(ball(r, 40, (-2.78, y + r, z)))
    add("shelf_balls", balls, 0.85)

    # A big vase on the floor, right of the sofa.
    add("floor_vase", vase(0.9, 0.2, 150, 200, (2.2, 0.0, 4.6)), 0.25)

    lights = [
        {"name": "ceiling spot", "type": "spot", "position": [0.0, 2.7, 2.9], "direction": [0, -1, 0],
         "cone_deg": 60, "power_w": 150, "spd": "D65"},
        {"name": "warm ceiling spot", "type": "spot", "position": [-1.4, 2.7, 4.2], "direction": [0, -1, 0],
         "cone_deg": 50, "power_w": 100, "spd": {"blackbody_k": 3000}},
    ]
    scene = {
        "spectrum": {"min_nm": 380, "max_nm": 780, "bins": 40},
        "camera": {
            "position": [0.4, 1.45, 0.0],
            "look_at": [0.0, 0.75, 3.6],
            "up": [0, 1, 0],
            "sensor": {"width_m": 0.036, "height_m": 0.024, "pixels": [240, 160]},
            "pinhole": {"distance_m": 0.022, "radius_m": 0.0005},
        },
        "lights": lights,
        "objects": [entry for entry, _ in files],
        "render": {"beams": 2000000, "seed": 1},
    }
    write_json(os.path.join(outdir, "room.json"), scene)
    return sum(n for _, n in files)


def main(argv):
    usage = "usage: make_mesh_scenes.py [--wavelengths-per-beam K] OUTDIR"
    wavelengths = None
    args = list(argv)
    if len(args) >= 2 and args[0] == "--wavelengths-per-beam":
        if args[1] not in ("1", "2", "4"):
            print(usage, file=sys.stderr)
            return 2
        wavelengths = int(args[1])
        args = args[2:]
    if len(args) != 1 or args[0].startswith("-"):
        print(usage, file=sys.stderr)
        return 2
    outdir = args[0]
    os.makedirs(outdir, exist_ok=True)
    n = sphere_mesh_scene(outdir, wavelengths)
    print("sphere_mesh.json: %d triangles" % n)
    n = room_scene(outdir)
    print("room.json: %d triangles" % n)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
