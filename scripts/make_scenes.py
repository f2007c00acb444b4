#!/usr/bin/env python3
"""Writes scenes/veach-mis.json and scenes/night-lights.json (generated so that their geometry is documented)."""
import json, math, random, pathlib

root = pathlib.Path(__file__).resolve().parent.parent / "scenes"

def norm(v):
    l = math.sqrt(sum(c * c for c in v)); return [c / l for c in v]
def sub(a, b): return [x - y for x, y in zip(a, b)]
def add(a, b): return [x + y for x, y in zip(a, b)]
def mul(a, s): return [x * s for x in a]
def cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
def r4(v): return [round(x, 4) for x in v]

def segments_cross(p1, p2, q1, q2):
    def side(o, a, b): return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    return side(q1, q2, p1) * side(q1, q2, p2) < 0 and side(p1, p2, q1) * side(p1, p2, q2) < 0

def check_plates(plates, targets):
    """In the y-z plane (every plate spans the same x): no segment from a point of one plate to a target (the
    camera, the top, middle and bottom of the light row) may cross another plate."""
    for k, (a, b) in enumerate(plates):
        for f in (0, 0.25, 0.5, 0.75, 1):
            s = [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f]
            for t in targets:
                for j, (c, d) in enumerate(plates):
                    assert j == k or not segments_cross(s, t, c, d), f"plate {j + 1} hides plate {k + 1} from {t}"

def veach():
    # Veach's MIS scene (thesis fig. 9.2): four glossy plates of increasing roughness reflect four sphere lights of
    # radius 0.0333 .. 0.9 and equal power (radiance ~ 1/r^2) toward the camera.
    cam, target = [0, 2, 15], [0, -2.6, 2.5]
    light_row = [0, 0, 0]
    lights = []
    for x, r, rad in [(-3.75, 0.0333, 901.803), (-1.25, 0.1, 100.0), (1.25, 0.3, 11.1111), (3.75, 0.9, 1.23457)]:
        lights.append({"type": "sphere", "center": [x, 0, 0], "radius": r, "radiance": [rad, rad, rad]})
    lights.append({"type": "sphere", "center": [10, 10, 4], "radius": 0.5, "radiance": [300, 300, 300]})
    shapes, materials = [], {"backdrop": {"type": "diffuse", "albedo": [0.25, 0.25, 0.25]}}
    # Plate centres (x, y, z), far+high to near+low, each tilted so that the camera sees the middle of the light row
    # mirrored at its centre. Placed (by a search) so that no plate hides another's view of the lights or of the
    # camera: check_plates() below fails otherwise. The first layout stacked the plates closer to the lights, and the
    # top plate hid the left half of the row from the second one.
    centres = [[0, -2.42, 0.84], [0, -3.07, 2.15], [0, -3.54, 3.85], [0, -3.68, 5.54]]
    depth = 1.0  # across the plate, in the y-z plane
    plates_yz = []
    for i, (p, rough) in enumerate(zip(centres, [0.05, 0.12, 0.25, 0.45])):
        n = norm(add(norm(sub(cam, p)), norm(sub(light_row, p))))
        t = norm(cross([1, 0, 0], n))  # in-plane direction across the plate (toward -z-ish)
        eu, ev = [8, 0, 0], mul(t, depth)
        origin = sub(sub(p, mul(eu, 0.5)), mul(ev, 0.5))
        plates_yz.append([[q[2], q[1]] for q in (origin, add(origin, ev))])
        # front face (edge_u x edge_v) must face the camera
        if sum(a * b for a, b in zip(cross(eu, ev), n)) < 0: origin, ev = add(origin, ev), mul(ev, -1)
        name = f"plate{i + 1}"
        materials[name] = {"type": "ggx", "f0": [0.85, 0.85, 0.85], "roughness": rough}
        shapes.append({"type": "quad", "name": name, "origin": r4(origin), "edge_u": r4(eu), "edge_v": r4(ev),
                       "material": name})
    check_plates(plates_yz, [[cam[2], cam[1]]] + [[light_row[2], light_row[1] + dy] for dy in (-0.9, 0, 0.9)])
    shapes.append({"type": "quad", "name": "floor", "origin": [-20, -4.2, -10], "edge_u": [0, 0, 40], "edge_v": [40, 0, 0],
                   "material": "backdrop"})
    shapes.append({"type": "quad", "name": "back", "origin": [-20, -4.2, -4], "edge_u": [40, 0, 0], "edge_v": [0, 30, 0],
                   "material": "backdrop"})
    return {"version": 1,
            "camera": {"type": "perspective", "from": cam, "to": target, "up": [0, 1, 0], "fov": 28},
            "film": {"width": 768, "height": 512},
            "render": {"integrator": "nee_mis", "spp": 64, "max_depth": 8, "sampler": "stratified", "seed": 0},
            "materials": materials, "shapes": shapes, "lights": lights}

def night():
    # A room at night lit only by 30 small coloured sphere lights (the lecture's case for light importance sampling).
    rnd = random.Random(7)
    materials = {"wall": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
                 "floor": {"type": "diffuse", "albedo": [0.5, 0.45, 0.4]},
                 "blue": {"type": "diffuse", "albedo": [0.2, 0.3, 0.6]},
                 "metal": {"type": "pbr", "base_color": [0.9, 0.9, 0.9], "metallic": 1, "roughness": 0.3}}
    W, H, D = 8, 3, 8
    shapes = [
        {"type": "quad", "name": "floor", "origin": [-W/2, 0, -D/2], "edge_u": [0, 0, D], "edge_v": [W, 0, 0], "material": "floor"},
        {"type": "quad", "name": "ceiling", "origin": [-W/2, H, -D/2], "edge_u": [W, 0, 0], "edge_v": [0, 0, D], "material": "wall"},
        {"type": "quad", "name": "back", "origin": [-W/2, 0, -D/2], "edge_u": [W, 0, 0], "edge_v": [0, H, 0], "material": "wall"},
        {"type": "quad", "name": "front", "origin": [-W/2, 0, D/2], "edge_u": [0, H, 0], "edge_v": [W, 0, 0], "material": "wall"},
        {"type": "quad", "name": "left", "origin": [-W/2, 0, -D/2], "edge_u": [0, H, 0], "edge_v": [0, 0, D], "material": "wall"},
        {"type": "quad", "name": "right", "origin": [W/2, 0, -D/2], "edge_u": [0, 0, D], "edge_v": [0, H, 0], "material": "wall"},
        {"type": "sphere", "center": [-1.2, 0.6, -1.0], "radius": 0.6, "material": "blue"},
        {"type": "sphere", "center": [1.0, 0.5, -0.3], "radius": 0.5, "material": "metal"},
        {"type": "sphere", "center": [0.2, 0.35, 1.2], "radius": 0.35, "material": "wall"},
    ]
    lights = []
    for _ in range(30):
        c = [rnd.uniform(-W/2 + 0.3, W/2 - 0.3), rnd.uniform(0.15, H - 0.15), rnd.uniform(-D/2 + 0.3, D/2 - 1.5)]
        r = rnd.uniform(0.03, 0.07)
        hue = rnd.random()
        col = [max(0.0, min(1.0, abs(hue * 6 - 3) - 1)), max(0.0, min(1.0, 2 - abs(hue * 6 - 2))),
               max(0.0, min(1.0, 2 - abs(hue * 6 - 4)))]
        power = 60 / (r * r) * 0.01
        lights.append({"type": "sphere", "center": r4(c), "radius": round(r, 4),
                       "radiance": r4([0.15 * power + 0.85 * power * k for k in col])})
    return {"version": 1,
            "camera": {"type": "perspective", "from": [0, 1.5, 3.9], "to": [0, 1.1, -1], "up": [0, 1, 0], "fov": 60},
            "film": {"width": 640, "height": 480},
            "render": {"integrator": "nee_mis", "spp": 64, "max_depth": 6, "sampler": "stratified", "seed": 0,
                       "light_selection": "importance"},
            "materials": materials, "shapes": shapes, "lights": lights}

for name, scene in [("veach-mis.json", veach()), ("night-lights.json", night())]:
    text = json.dumps(scene, indent=1)
    (root / name).write_text(text + "\n")
    print("wrote", root / name)
