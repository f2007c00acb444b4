#!/usr/bin/env bash
# Smoke test of `lumis bench`: tiny settings (--quick: a 20k-triangle generated room and cornell-sphere at 32x32,
# 1 spp), the JSON report parses and has every field, the rays split by kind add up, the ratios to the raw rates
# and the time the target leaves lumis follow from the report's own rates, counts and times, the replay of each
# render's own rays holds all of them, --write-large-scene writes a glTF that `lumis render` loads, and its usage
# errors (a name other than .glb, any other option beside it, an --assets folder that does not exist) exit 2.
# Speeds are not checked (shared machines). Usage: bench.sh path/to/lumis
set -uo pipefail
LUMIS=${1:?usage: bench.sh path/to/lumis}
source "$(dirname "$0")/common.bash"
need python3 python3  # checks the JSON report

"$LUMIS" bench --quick --threads 2 --json "$T/bench.json" >"$T/out" 2>"$T/err" ||
  { rc=$?; cat "$T/out" "$T/err"; fail "lumis bench --quick exited $rc"; }
grep -q "Raw Embree" "$T/out" || fail "no raw-throughput table: $(cat "$T/out")"
grep -q "Targets" "$T/out" || fail "no targets section: $(cat "$T/out")"
grep -q "Embree by kind of ray" "$T/out" || fail "no per-kind table: $(cat "$T/out")"
grep -q "What the rays/s target leaves lumis's own code" "$T/out" || fail "no budget section: $(cat "$T/out")"

python3 - "$T/bench.json" <<'PY' || fail "JSON report: $(cat "$T/bench.json")"
import json, sys
doc = json.load(open(sys.argv[1]))
for k in ("cpu", "cores", "load_average_start"):
    assert k in doc["machine"], k
assert doc["settings"]["quick"] is True and doc["settings"]["raw_rays"] == 4096, doc["settings"]
assert doc["lumis_version"], doc.get("lumis_version")
assert doc["settings"]["threads"] == min(2, doc["machine"]["cores"]), doc["settings"]  # capped at the cores
names = [s["name"] for s in doc["scenes"]]
assert names == ["large", "cornell-sphere"], names
variants = {"uniform", "bsdf", "light", "mis", "nee_mis"}
for s in doc["scenes"]:
    assert "error" not in s, s
    for k in ("triangles", "lights", "load_seconds", "bvh_build_seconds", "memory", "raw_rays_per_s", "variants",
              "thread_scaling", "file_bytes"):
        assert k in s, (s["name"], k)
    assert s["load_seconds"] > 0 and s["bvh_build_seconds"] > 0
    assert s["memory"]["peak_rss_bytes"] > 0
    raw = s["raw_rays_per_s"]
    for k in ("camera_intersect1", "camera_intersect16", "bounce_intersect1", "bounce_intersect16",
              "shadow_occluded1", "shadow_occluded16", "light_query", "bounce_intersect1_shuffled",
              "shadow_occluded1_shuffled"):
        assert raw[k] > 0, (s["name"], k, raw[k])
    own = s["own_rays_per_s"]  # nee_mis's own rays by kind: camera, bounce and shadow rays, no light queries
    assert own["integrator"] == "nee_mis", own
    # A figure not measured is null, as the table's '-' (it was 0.0, a rate that reads as infinitely slow).
    assert own["camera"] > 0 and own["bounce"] > 0 and own["shadow"] > 0 and own["light_query"] is None, own
    bpt = s["memory"]["bytes_per_triangle"]  # measured from 10,000 triangles on: the large room, not the box
    assert (bpt > 0) if s["triangles"] >= 10000 else (bpt is None), (s["name"], s["memory"])
    assert {v["integrator"] for v in s["variants"]} == variants
    for v in s["variants"]:
        kinds = v["rays_by_kind"]
        assert sum(kinds.values()) == v["rays"], (s["name"], v)
        assert kinds["camera"] == v["samples"] == 32 * 32, (s["name"], v)
        for k in ("samples_per_s", "rays_per_s", "raw_mix_rays_per_s", "ratio_to_raw", "ratio_to_raw_packets",
                  "ratio_to_own_rays", "ratio_to_raw_shuffled", "embree_share"):
            assert v[k] > 0, (s["name"], v["integrator"], k)
        # One repetition (--quick): each ratio is Embree's time for the render's mix of rays at the raw rates
        # above over the render's time, the shuffled one with the bounce and shadow rays' shuffled rates.
        for key, bounce, shadow in (("ratio_to_raw", "bounce_intersect1", "shadow_occluded1"),
                                    ("ratio_to_raw_shuffled", "bounce_intersect1_shuffled",
                                     "shadow_occluded1_shuffled")):
            rates = {"camera": raw["camera_intersect1"], "bounce": raw[bounce], "shadow": raw[shadow],
                     "light_query": raw["light_query"]}
            embree_s = sum(n / rates[k] for k, n in kinds.items() if n)
            expected = embree_s * v["rays_per_s"] / v["rays"]
            assert abs(v[key] - expected) <= 1e-9 * expected, (s["name"], v["integrator"], key, v[key], expected)
        assert v["replay_rays"] == v["rays"], (s["name"], v["integrator"], "the replay must hold every ray")
        # The budget: CPU time per sample split by the replay's Embree share; at the target ratio the same Embree
        # time in ratio / target of the render's time.
        b, per = v["budget_cpu_s_per_sample"], v["cpu_seconds"] / v["samples"]
        assert b["target_ratio"] == 0.7 and per > 0, (s["name"], v["integrator"], b)
        for key, expected in (("render", per), ("embree", v["embree_share"] * per),
                              ("lumis", (1 - v["embree_share"]) * per),
                              ("lumis_at_target", per * v["ratio_to_raw"] / 0.7 - v["embree_share"] * per)):
            assert abs(b[key] - expected) <= 1e-9 * per, (s["name"], v["integrator"], key, b[key], expected)
    nee = next(v for v in s["variants"] if v["integrator"] == "nee_mis")
    mis = next(v for v in s["variants"] if v["integrator"] == "mis")
    assert nee["rays_by_kind"]["shadow"] > 0 and nee["rays_by_kind"]["light_query"] == 0
    assert mis["rays_by_kind"]["light_query"] > 0 and mis["rays_by_kind"]["shadow"] == 0
    ts = s["thread_scaling"]
    assert ts["integrator"] == "nee_mis" and ts["samples_per_s_1"] > 0 and ts["speedup"] > 0
    for k in ("camera_packets", "shadow_packets", "bounce_packets"):
        assert s[k]["samples_per_s_single_rays"] > 0 and s[k]["speedup_cpu"] > 0, (s["name"], k, s[k])
large = doc["scenes"][0]
assert large["triangles"] >= 20000 and large["generate_seconds"] > 0
assert large["raw_rays_per_s"]["bounce_hit_fraction"] > 0.99, "the generated room must be closed"
assert any(t["scene"] == "cornell-sphere" for t in doc["targets"])
# Each target's name says what it is on its own (the table indents the second views under the first).
assert all(t["name"] == t["name"].strip() and t["name"].split()[0] in ("nee_mis", "thread", "load", "peak")
           for t in doc["targets"]), [t["name"] for t in doc["targets"]]
PY

# The generated scene on its own, through the real loader.
"$LUMIS" bench --write-large-scene "$T/large.glb" --large-triangles 5000 2>"$T/err" || fail "write: $(cat "$T/err")"
[ -s "$T/large.glb" ] || fail "no .glb written"
"$LUMIS" render "$T/large.glb" --width 16 --height 16 --spp 1 -q -o "$T/large.png" 2>"$T/err" ||
  fail "render of the generated scene: $(cat "$T/err")"
# A scene with no target at one thread: the Targets heading says so rather than standing empty.
"$LUMIS" bench "$T/large.glb" --quick --threads 1 --integrator bsdf >"$T/out" 2>"$T/err" ||
  fail "bench of the generated scene: $(cat "$T/err")"
grep -A1 "^Targets" "$T/out" | grep -q "^  none measured here: the rays/s targets are cornell-sphere's" ||
  fail "no targets, no word: $(cat "$T/out")"
grep -q "^Raw Embree, Mrays/s (wall clock), 1 thread " "$T/out" || fail "one thread, in words: $(cat "$T/out")"
# Usage errors (exit 2, named on stderr): the room written to anything but a .glb, an assets folder that is not one.
"$LUMIS" bench --write-large-scene "$T/room.gltf" >"$T/out" 2>"$T/err"
[ $? = 2 ] || fail "--write-large-scene to a .gltf should exit 2"
grep -q "expected a .glb file name" "$T/err" || fail "--write-large-scene message: $(cat "$T/err")"
[ ! -e "$T/room.gltf" ] || fail "--write-large-scene wrote a .gltf"
"$LUMIS" bench --write-large-scene "$T/ROOM.GLB" --large-triangles 200 2>"$T/err" ||
  fail ".GLB refused: $(cat "$T/err")"
# --write-large-scene writes the room and exits: any other option (a scene, a render override, --json, even the
# hidden --time) is refused by name rather than ignored, and nothing is written.
for extra in "--spp 4" "@large" "--json $T/wl.json" "--time 1"; do
  "$LUMIS" bench --write-large-scene "$T/wl.glb" $extra >"$T/out" 2>"$T/err"
  [ $? = 2 ] || fail "--write-large-scene with $extra should exit 2"
  name=${extra% *}; [ "$name" = @large ] && name="a scene"
  grep -qF "only writes the generated room and exits (with --large-triangles); $name does not apply" "$T/err" ||
    fail "--write-large-scene with $extra: $(cat "$T/err")"
  [ ! -e "$T/wl.glb" ] && [ ! -e "$T/wl.json" ] || fail "--write-large-scene with $extra wrote a file"
done
# --large-triangles with --quick sizes the room: --quick's 20,000 is a default, as its one repetition is.
"$LUMIS" bench @large --quick --large-triangles 500 --integrator nee_mis --threads 2 --json "$T/small.json" \
  >"$T/out" 2>"$T/err" || fail "bench @large --large-triangles 500: $(cat "$T/err")"
! grep -q "warning" "$T/err" || fail "warning for --large-triangles with @large: $(cat "$T/err")"
python3 -c 'import json, sys; t = json.load(open(sys.argv[1]))["scenes"][0]["triangles"]; assert 500 <= t < 20000, t' \
  "$T/small.json" || fail "--quick --large-triangles 500 did not size the room"
# --assets and --large-triangles where they cannot take effect are named in warnings; the run goes on.
"$LUMIS" bench "$SCENE" --quick --integrator nee_mis --assets "$T" --large-triangles 500 >"$T/out" 2>"$T/err" ||
  fail "bench with --assets and scenes named: $(cat "$T/err")"
ASSETS_WARNING="warning: --assets only adds the shared glTF models to the default scene list; ignored"
grep -qF -- "$ASSETS_WARNING when scenes are named" "$T/err" || fail "--assets with scenes named: $(cat "$T/err")"
grep -qF -- "warning: --large-triangles only sizes the generated room; ignored, as the scenes named do not include \
@large" "$T/err" || fail "--large-triangles without @large: $(cat "$T/err")"
"$LUMIS" bench --quick --integrator nee_mis --assets "$T" >"$T/out" 2>"$T/err" ||
  fail "--quick --assets: $(cat "$T/err")"
grep -qF -- "$ASSETS_WARNING with --quick" "$T/err" || fail "--assets with --quick: $(cat "$T/err")"
"$LUMIS" bench --quick --assets "$T/no-such-folder" >"$T/out" 2>"$T/err"
[ $? = 2 ] || fail "--assets on a missing folder should exit 2"
grep -q "no-such-folder" "$T/err" || fail "--assets message: $(cat "$T/err")"
"$LUMIS" bench "$T/missing.json" --quick >"$T/out" 2>"$T/err"
[ $? = 1 ] || fail "a missing scene should exit 1"
grep -q "missing.json" "$T/err" || fail "missing-scene message: $(cat "$T/err")"
"$LUMIS" bench @larg --quick >"$T/out" 2>"$T/err"
[ $? = 1 ] || fail "a misspelt @large should exit 1"
grep -qF "@larg: file not found (@large is the generated scene)" "$T/err" || fail "@larg message: $(cat "$T/err")"
# A scene that fails to load: its error in the table, and no empty tables after it when no scene was measured.
printf '{"version": 1, "shapes": [' >"$T/broken.json"
"$LUMIS" bench "$T/broken.json" --quick >"$T/out" 2>"$T/err"
[ $? = 1 ] || fail "a broken scene should exit 1"
grep -q "^broken .*error: .*broken.json:1:" "$T/out" || fail "broken scene's row: $(cat "$T/out")"
grep -q "^No scene was measured.$" "$T/out" || fail "no 'No scene was measured.': $(cat "$T/out")"
grep -q "Raw Embree\|Targets" "$T/out" && fail "empty tables after a run that measured nothing: $(cat "$T/out")"

# More threads than cores are capped, as render caps them, and said: the scaling figures divide by the threads.
"$LUMIS" bench "$SCENE" --quick --integrator bsdf --threads 1024 --json "$T/t.json" >"$T/out" 2>"$T/err" ||
  fail "bench --threads 1024: $(cat "$T/err")"
grep -q "warning: --threads 1024 is more than the [0-9]* cores; measuring with" "$T/err" ||
  fail "no warning for --threads beyond the cores: $(cat "$T/err")"
python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(d["settings"]["threads"] != d["machine"]["cores"])' "$T/t.json" \
  || fail "--threads 1024 not capped at the cores: $(head -c 300 "$T/t.json")"
grep -q "TBB" "$T/err" && fail "TBB warned of more threads than cores: $(cat "$T/err")"

# The default list without the shared glTF models (an --assets folder without them): measured, and said.
"$LUMIS" bench --assets "$T" --repeat 1 --spp 1 --width 8 --large-triangles 100 --raw-rays 16 >"$T/out" 2>"$T/err" ||
  fail "bench of the default list without the models: $(cat "$T/err")"
grep -qF "warning: $T: no gltf/ToyCar/glTF/ToyCar.gltf, gltf/MetalRoughSpheresNoTextures/glTF/" "$T/err" ||
  fail "no warning for the missing glTF models: $(cat "$T/err")"
echo "ok"
