#!/usr/bin/env python3
"""Writes the regression cases: tests/regression/cases/<case>.json (one self-contained scene per case, with its
integrator and settings in "render") and tests/regression/cases.txt (case, test spp, reference spp).

A case is a scene plus render settings; scenes are generated here so that variants of one scene cannot drift apart.
Every scene is 32x32. The design rule (see README.md): each case's estimator must be in its central-limit regime at
the test's spp, so uniform/bsdf cases only see broad lights, and light-only cases only rough surfaces."""
import copy, json, math, pathlib

here = pathlib.Path(__file__).resolve().parent
SIZE = 32


def sub(a, b): return [x - y for x, y in zip(a, b)]
def cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
def dot(a, b): return sum(x * y for x, y in zip(a, b))


MATERIALS = {
    "white": {"type": "diffuse", "albedo": [0.73, 0.73, 0.73]},
    "red": {"type": "diffuse", "albedo": [0.65, 0.05, 0.05]},
    "green": {"type": "diffuse", "albedo": [0.12, 0.45, 0.15]},
    "checker": {"type": "diffuse", "albedo": [0.9, 0.9, 0.9], "texture": "../checker.png"},
    "rough_gold": {"type": "ggx", "f0": [0.95, 0.64, 0.54], "roughness": 0.75},
    "blue_plastic": {"type": "pbr", "base_color": [0.2, 0.4, 0.8], "metallic": 0, "roughness": 0.7},
    "textured_pbr": {"type": "pbr", "base_color": [1, 1, 1], "metallic": 1, "roughness": 1,
                     "base_color_texture": "../checker.png", "metallic_roughness_texture": "../mr.png",
                     "normal_texture": "../normal.png", "normal_scale": 1},
}


def box_shapes():
    """Cornell-like box [-1,1] x [0,2] x [-1,..], open at the front, with a textured floor, a rough GGX sphere, a
    dielectric pbr sphere and a fully textured pbr panel (base colour, metallic-roughness, normal map)."""
    return [
        {"type": "quad", "name": "floor", "origin": [-1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0], "material": "checker"},
        {"type": "quad", "name": "ceiling", "origin": [-1, 2, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "material": "white"},
        {"type": "quad", "name": "back", "origin": [-1, 0, -1], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "white"},
        {"type": "quad", "name": "left", "origin": [-1, 0, -1], "edge_u": [0, 2, 0], "edge_v": [0, 0, 2], "material": "red"},
        {"type": "quad", "name": "right", "origin": [1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [0, 2, 0], "material": "green"},
        {"type": "quad", "name": "panel", "origin": [-0.15, 0.7, -0.98], "edge_u": [1.0, 0, 0], "edge_v": [0, 0.9, 0],
         "material": "textured_pbr"},
        {"type": "sphere", "name": "gold", "center": [-0.45, 0.35, -0.3], "radius": 0.35, "material": "rough_gold"},
        {"type": "sphere", "name": "plastic", "center": [0.45, 0.3, 0.25], "radius": 0.3, "material": "blue_plastic"},
    ]


def outward_mesh(center, positions, tris):
    """Orient every triangle counter-clockwise seen from outside (front face away from `center`)."""
    idx = []
    for a, b, c in tris:
        n = cross(sub(positions[b], positions[a]), sub(positions[c], positions[a]))
        mid = [sum(positions[i][k] for i in (a, b, c)) / 3 for k in range(3)]
        idx += [a, b, c] if dot(n, sub(mid, center)) > 0 else [a, c, b]
    return idx


def octahedron(center, r):
    cx, cy, cz = center
    pos = [[cx + r, cy, cz], [cx - r, cy, cz], [cx, cy + r, cz], [cx, cy - r, cz], [cx, cy, cz + r], [cx, cy, cz - r]]
    tris = [(x, y, z) for x in (0, 1) for y in (2, 3) for z in (4, 5)]
    return pos, outward_mesh(center, pos, tris)


def scene(shapes, lights, materials=None, camera=None, **render):
    # No Russian roulette by default: q = min(0.95, max(beta)) renormalises the largest channel, so after a green
    # wall a surviving path's red channel is boosted ~10x with probability ~0.1 (rare, large samples; see README).
    r = {"integrator": "nee_mis", "spp": 128, "max_depth": 4, "rr_depth": 0, "sampler": "stratified", "seed": 1}
    r.update(render)
    return {"version": 1,
            "camera": camera or {"type": "perspective", "from": [0, 1, 3.9], "to": [0, 1, 0], "up": [0, 1, 0], "fov": 40},
            "film": {"width": SIZE, "height": SIZE},
            "render": r,
            "materials": copy.deepcopy(materials or MATERIALS),
            "shapes": shapes, "lights": lights}


# --- the scenes --------------------------------------------------------------------------------------------------

# A broad ceiling quad light (1.2 x 1.2, facing down): solid angle 0.3-1 sr from most of the box, so uniform and
# BSDF sampling find it often enough.
QUAD_LIGHT = {"type": "quad", "origin": [-0.6, 1.99, -0.6], "edge_u": [1.2, 0, 0], "edge_v": [0, 0, 1.2],
              "radiance": [4, 4, 4]}


def box(**render):
    return scene(box_shapes(), [QUAD_LIGHT], **render)


def box_area(**render):
    return scene(box_shapes(), [dict(QUAD_LIGHT, sampling="area")], **render)


def sphere(**render):
    return scene(box_shapes(), [{"type": "sphere", "center": [0, 1.5, 0.1], "radius": 0.25, "radiance": [12, 11, 9]}],
                 **render)


def mesh(sampling, **render):
    """An emissive octahedron (mesh shape with `emission`) and a textured emissive panel on the left wall (a mesh
    whose pbr material has an emissive texture): two mesh lights, both with the given triangle sampling."""
    materials = copy.deepcopy(MATERIALS)
    materials["lamp"] = {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}
    materials["glow"] = {"type": "pbr", "base_color": [0.1, 0.1, 0.1], "metallic": 0, "roughness": 1,
                         "emissive": [3, 3, 3], "emissive_texture": "../emissive.png"}
    pos, idx = octahedron([0.1, 1.45, 0.0], 0.3)
    shapes = box_shapes()
    shapes.append({"type": "mesh", "name": "octahedron", "positions": pos, "indices": idx, "material": "lamp",
                   "emission": [5, 4.5, 4], "sampling": sampling})
    # On the left wall, facing +x; uv (0,0) at the first vertex.
    shapes.append({"type": "mesh", "name": "glow_panel",
                   "positions": [[-0.99, 0.5, -0.7], [-0.99, 1.4, -0.7], [-0.99, 1.4, 0.3], [-0.99, 0.5, 0.3]],
                   "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "indices": [0, 1, 2, 0, 2, 3], "material": "glow",
                   "sampling": sampling})
    return scene(shapes, [], materials=materials, **render)


def outdoor_shapes():
    return [
        {"type": "quad", "name": "ground", "origin": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0], "material": "checker"},
        {"type": "quad", "name": "panel", "origin": [-1.1, 0, -0.9], "edge_u": [1.0, 0, -0.3], "edge_v": [0, 1.0, 0],
         "material": "textured_pbr"},
        {"type": "sphere", "name": "gold", "center": [-0.5, 0.35, 0.3], "radius": 0.35, "material": "rough_gold"},
        {"type": "sphere", "name": "plastic", "center": [0.55, 0.4, -0.2], "radius": 0.4, "material": "blue_plastic"},
        {"type": "sphere", "name": "white", "center": [0.3, 0.2, 0.8], "radius": 0.2, "material": "white"},
    ]


OUTDOOR_CAMERA = {"type": "perspective", "from": [0, 1.6, 3.6], "to": [0, 0.35, 0], "up": [0, 1, 0], "fov": 45}


def env_const(**render):
    return scene(outdoor_shapes(), [{"type": "environment", "radiance": [0.8, 0.9, 1.0]}], camera=OUTDOOR_CAMERA,
                 **render)


def env_image(**render):
    return scene(outdoor_shapes(), [{"type": "environment", "file": "../sky.hdr", "scale": 0.8, "rotation": 30}],
                 camera=OUTDOOR_CAMERA, **render)


def multi(**render):
    """Four lights of very different power and size: an area-sampled ceiling quad light, an emissive sphere shape
    (a light with a material), an emissive octahedron (spherical triangles) and a dim constant sky seen through the
    open front. The light selection strategy matters here."""
    materials = copy.deepcopy(MATERIALS)
    materials["lamp"] = {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}
    shapes = box_shapes()
    shapes.append({"type": "sphere", "name": "orb", "center": [0.7, 1.6, -0.6], "radius": 0.15, "material": "white",
                   "emission": [20, 8, 4]})
    pos, idx = octahedron([-0.6, 1.5, 0.2], 0.2)
    shapes.append({"type": "mesh", "name": "octahedron", "positions": pos, "indices": idx, "material": "lamp",
                   "emission": [1, 5, 2]})
    lights = [{"type": "quad", "origin": [-0.3, 1.99, -0.5], "edge_u": [0.6, 0, 0], "edge_v": [0, 0, 0.6],
               "radiance": [5, 5, 6], "sampling": "area"},
              {"type": "environment", "radiance": [0.3, 0.3, 0.4]}]
    return scene(shapes, lights, materials=materials, **render)


# --- the cases: (name, scene, test spp, reference spp) ----------------------------------------------------------
# The group (the name up to the first "_", or "env_const"/"env_image") is a set of cases whose images have the same
# expectation: `scripts/regression.sh --regenerate` cross-checks their references against each other.

CASES = [
    # every integrator variant on the quad-lit box (stratified sampler, importance selection, balance heuristic)
    ("box_uniform", box(integrator="uniform"), 256, 16384),
    ("box_uniform_solid_angle", box(integrator="uniform", uniform_measure="solid_angle"), 256, 16384),
    ("box_bsdf", box(integrator="bsdf"), 128, 8192),
    ("box_light", box(integrator="light"), 128, 8192),
    ("box_mis", box(integrator="mis", max_depth=2), 128, 8192),
    ("box_nee_mis", box(integrator="nee_mis"), 128, 8192),
    # samplers
    ("box_nee_mis_sobol", box(integrator="nee_mis", sampler="sobol"), 128, 8192),
    ("box_mis_independent", box(integrator="mis", sampler="independent", max_depth=2), 128, 8192),
    # quad light sampled by area
    ("box_area_light", box_area(integrator="light"), 128, 8192),
    # sphere light
    ("sphere_light", sphere(integrator="light"), 128, 8192),
    ("sphere_mis_07", sphere(integrator="mis", mis_light_probability=0.7, max_depth=2), 128, 8192),
    ("sphere_nee_mis_power", sphere(integrator="nee_mis", mis_heuristic="power"), 128, 8192),
    # mesh lights (an emissive mesh shape and a textured emissive material), both triangle samplings
    ("mesh_spherical_light", mesh("spherical_triangle", integrator="light"), 128, 8192),
    ("mesh_spherical_nee_mis", mesh("spherical_triangle", integrator="nee_mis"), 128, 8192),
    ("mesh_area_light", mesh("area", integrator="light"), 128, 8192),
    # constant environment
    ("env_const_uniform", env_const(integrator="uniform"), 128, 8192),
    ("env_const_bsdf", env_const(integrator="bsdf"), 128, 8192),
    ("env_const_nee_mis_rr", env_const(integrator="nee_mis", rr_depth=2), 128, 8192),
    # image environment
    ("env_image_bsdf", env_image(integrator="bsdf"), 128, 8192),
    ("env_image_light", env_image(integrator="light"), 128, 8192),
    ("env_image_mis", env_image(integrator="mis", max_depth=2), 128, 8192),
    ("env_image_nee_mis", env_image(integrator="nee_mis"), 128, 8192),
    # light selection strategies with several lights
    ("multi_light_uniform", multi(integrator="light", light_selection="uniform"), 128, 8192),
    ("multi_light_power", multi(integrator="light", light_selection="power"), 128, 8192),
    ("multi_light_importance", multi(integrator="light", light_selection="importance"), 128, 8192),
    ("multi_mis_power", multi(integrator="mis", light_selection="power", max_depth=2), 128, 8192),
    ("multi_nee_mis_importance", multi(integrator="nee_mis", light_selection="importance"), 128, 8192),
]

if __name__ == "__main__":
    out = here / "cases"
    out.mkdir(exist_ok=True)
    for old in out.glob("*.json"):
        old.unlink()
    lines = ["# case test_spp reference_spp group  (written by make_scenes.py; cases of a group have the same expectation)"]
    for name, sc, spp, ref_spp in CASES:
        sc["render"]["spp"] = spp
        (out / f"{name}.json").write_text(json.dumps(sc, indent=1) + "\n")
        group = "_".join(name.split("_")[:2]) if name.startswith("env_") else name.split("_")[0]
        if sc["render"]["max_depth"] != 4:
            group += f"_depth{sc['render']['max_depth']}"
        lines.append(f"{name} {spp} {ref_spp} {group}")
    (here / "cases.txt").write_text("\n".join(lines) + "\n")
    print(f"wrote {len(CASES)} cases to {out}")
