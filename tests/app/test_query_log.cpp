// The query logs `lumis bench` replays to time Embree on exactly a render's rays (docs/performance.md):
//  - a render's logs hold every ray it counted, by kind and by call (camera packets, bounce rays, shadow packets,
//    light queries), with packets on and off; the same logs for any thread count; nothing is logged outside;
//  - the replay traces what was logged: the same hits as Geometry's own queries, as packets and as single rays.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "app/bench.h"
#include "app/scene_loader.h"
#include "tests/support/render_film.h"

namespace lumis {
namespace {

using Call = QueryLog::Call;

std::unique_ptr<Scene> cornell() {
  auto scene = load_scene(std::string(LUMIS_SOURCE_DIR) + "/scenes/cornell-sphere.json");
  scene->settings.width = 37;
  scene->settings.height = 22;  // partial tiles and partial 4x4 packets
  return scene;
}

struct Logged {
  std::vector<QueryLog> logs;
  RenderStats stats;
};

Logged render_logged(const Scene& scene, int threads, bool packets = true) {
  Logged out;
  RenderOptions ro;
  ro.threads = threads;
  ro.camera_packets = ro.shadow_packets = ro.bounce_packets = packets;
  ro.query_logs = &out.logs;
  out.stats = test::render_film(scene, 3, ro).stats;
  return out;
}

std::map<Call, uint64_t> rays_by_call(const std::vector<QueryLog>& logs) {
  std::map<Call, uint64_t> n;
  for (const QueryLog& log : logs) {
    uint64_t in_calls = 0;
    for (const QueryLog::Entry& e : log.calls) {
      EXPECT_EQ(e.first, in_calls);
      EXPECT_GE(e.n, 1);
      EXPECT_LE(e.n, 16);
      n[e.call] += e.n;
      in_calls += e.n;
    }
    EXPECT_EQ(in_calls, log.rays.size());
  }
  return n;
}

// Every ray RenderStats counts is in the logs, as the call that traced it. A query left out of the log (or logged
// twice) breaks the equality of its kind.
TEST(QueryLog, HoldsEveryRayOfTheRenderByKind) {
  auto scene = cornell();
  for (const char* variant : {"nee_mis", "mis", "light"}) {
    scene->settings.integrator = variant;
    for (const bool packets : {true, false}) {
      SCOPED_TRACE(std::string(variant) + (packets ? ", packets" : ", one by one"));
      const Logged l = render_logged(*scene, 2, packets);
      EXPECT_EQ(l.logs.size(), 3u * 2u);  // 16x16 tiles over 37x22 pixels
      std::map<Call, uint64_t> n = rays_by_call(l.logs);
      const uint64_t camera = l.stats.samples, shadow = l.stats.shadow_rays, lq = l.stats.light_queries;
      ASSERT_GT(camera, 0u);
      EXPECT_EQ(n[Call::Intersect16], packets ? camera : 0);
      // Bounce rays: in incoherent packets, but for a bounce's lone last ray of a 16-lane chunk.
      EXPECT_EQ(n[Call::Intersect1] + n[Call::Intersect16Incoherent],
                l.stats.rays - shadow - lq - (packets ? camera : 0));
      if (!packets) {
        EXPECT_EQ(n[Call::Intersect16Incoherent], 0u);
      } else {
        EXPECT_GT(n[Call::Intersect16Incoherent], 10 * n[Call::Intersect1]);
      }
      EXPECT_EQ(n[Call::Occluded16] + n[Call::Occluded1], shadow);
      if (!packets) {
        EXPECT_EQ(n[Call::Occluded16], 0u);
      } else if (shadow > 0) {
        EXPECT_GT(n[Call::Occluded16], n[Call::Occluded1]);
      }
      EXPECT_EQ(n[Call::LightHits], lq);
      EXPECT_EQ(std::string(variant) == "mis", lq > 0);
    }
  }
}

// A tile's log depends on the tile only, like its pixels: the same calls and rays, bit for bit, whatever the
// thread count.
TEST(QueryLog, SameForAnyThreadCount) {
  auto scene = cornell();
  const Logged a = render_logged(*scene, 1), b = render_logged(*scene, 2);
  ASSERT_EQ(a.logs.size(), b.logs.size());
  for (size_t t = 0; t < a.logs.size(); ++t) {
    const QueryLog &x = a.logs[t], &y = b.logs[t];
    ASSERT_EQ(x.rays.size(), y.rays.size()) << "tile " << t;
    ASSERT_EQ(x.calls.size(), y.calls.size()) << "tile " << t;
    EXPECT_EQ(0, std::memcmp(x.rays.data(), y.rays.data(), x.rays.size() * sizeof(Ray))) << "tile " << t;
    for (size_t i = 0; i < x.calls.size(); ++i)
      EXPECT_TRUE(x.calls[i].call == y.calls[i].call && x.calls[i].n == y.calls[i].n) << "tile " << t;
  }
}

// Recording is per thread and only while a log is set: queries after the render, or on a thread with no log, go
// nowhere; a thread with a log set records its own queries.
TEST(QueryLog, OnlyWhileSet) {
  auto scene = cornell();
  Logged l = render_logged(*scene, 1);
  size_t total = 0;
  for (const QueryLog& log : l.logs) total += log.rays.size();
  const Ray ray{{0, 1, 3.9f}, {0, 0, -1}};
  Hit hit;
  ASSERT_TRUE(scene->geometry.intersect(ray, hit));
  size_t after = 0;
  for (const QueryLog& log : l.logs) after += log.rays.size();
  EXPECT_EQ(after, total);

  QueryLog mine;
  Geometry::record_queries(&mine);
  scene->geometry.intersect(ray, hit);
  bool occluded[2];
  const Ray two[2] = {ray, ray};
  scene->geometry.occluded16(two, 2, occluded);
  Geometry::record_queries(nullptr);
  scene->geometry.occluded(ray);
  ASSERT_EQ(mine.calls.size(), 2u);
  EXPECT_EQ(mine.calls[0].call, Call::Intersect1);
  EXPECT_EQ(mine.calls[1].call, Call::Occluded16);
  EXPECT_EQ(mine.calls[1].n, 2);
  EXPECT_EQ(mine.rays.size(), 3u);
}

// The replay traces the logged rays: its counts (closest hits that hit, occluded shadow rays, light queries that
// meet a light) equal Geometry's own answers for the same rays, as packets and as single rays. Camera rays and
// shadow rays are aimed well inside surfaces, so packet and single-ray kernels cannot disagree at an edge.
TEST(Replay, TracesWhatWasLogged) {
  auto scene = cornell();
  Camera camera = scene->camera;
  camera.prepare(16, 16);
  QueryLog log;
  Geometry::record_queries(&log);
  Ray cam[16];
  for (int i = 0; i < 16; ++i) cam[i] = camera.generate_ray({4.5f + (i % 4), 4.5f + float(i / 4)});
  Hit hits[16];
  bool found[16];
  scene->geometry.intersect16(cam, 16, hits, found);
  Ray shadow[16];
  size_t occluded_expected = 0, hits_expected = 0, lq_expected = 0;
  for (int i = 0; i < 16; ++i) {
    ASSERT_TRUE(found[i]);
    ++hits_expected;
    // Through the sphere light's centre (a light query meets it) and toward the floor behind the copper sphere.
    const Vec3 target = i % 2 ? Vec3{0, 1.7f, 0} : Vec3{0.1f * float(i) - 0.8f, 0.01f, -0.9f};
    shadow[i] = spawn_ray_to(hits[i], target, {}, 0);  // a point in free space: no offset
  }
  bool occ[16];
  scene->geometry.occluded16(shadow, 16, occ);
  for (int i = 0; i < 16; ++i) occluded_expected += occ[i];
  for (int i = 0; i < 3; ++i) occluded_expected += scene->geometry.occluded(shadow[i]);
  LightHitRecord lh[64];
  for (int i = 0; i < 16; ++i) lq_expected += scene->geometry.all_light_hits(shadow[i], lh, 64) > 0;
  Geometry::record_queries(nullptr);
  EXPECT_GT(occluded_expected, 0u);
  EXPECT_LT(occluded_expected, 19u);
  EXPECT_GT(lq_expected, 0u);
  const size_t expected = hits_expected + occluded_expected + lq_expected;
  for (const bool single : {false, true}) {
    const ReplayTiming r = replay_queries(scene->geometry, {log}, 2, single);
    EXPECT_EQ(r.rays, 16u + 16u + 3u + 16u);
    EXPECT_EQ(r.hits, expected) << (single ? "single rays" : "as called");
    EXPECT_GT(r.wall, 0);
  }
  // Kind by kind (the benchmark's per-kind table): each kind's calls alone, and together they are the whole log.
  const size_t kind_rays[kRayKinds] = {16, 0, 16 + 3, 16};
  const size_t kind_hits[kRayKinds] = {hits_expected, 0, occluded_expected, lq_expected};
  for (int k = 0; k < kRayKinds; ++k) {
    const ReplayTiming r = replay_queries(scene->geometry, {log}, 2, true, RayKind(k));
    EXPECT_EQ(r.rays, kind_rays[k]) << "kind " << k;
    EXPECT_EQ(r.hits, kind_hits[k]) << "kind " << k;
  }
}

// Every logged call is of one kind, and a render's logs split by kind as RenderStats splits its rays.
TEST(Replay, KindsSplitARenderAsItsCounters) {
  EXPECT_EQ(ray_kind(Call::Intersect16), RayKind::Camera);
  EXPECT_EQ(ray_kind(Call::Intersect16Incoherent), RayKind::Bounce);
  EXPECT_EQ(ray_kind(Call::Intersect1), RayKind::Bounce);
  EXPECT_EQ(ray_kind(Call::Occluded1), RayKind::Shadow);
  EXPECT_EQ(ray_kind(Call::Occluded16), RayKind::Shadow);
  EXPECT_EQ(ray_kind(Call::LightHits), RayKind::LightQuery);
  auto scene = cornell();
  for (const char* variant : {"nee_mis", "mis"}) {
    SCOPED_TRACE(variant);
    scene->settings.integrator = variant;
    const Logged l = render_logged(*scene, 2);
    const RenderStats& st = l.stats;
    const uint64_t expected[kRayKinds] = {st.samples, st.rays - st.samples - st.shadow_rays - st.light_queries,
                                          st.shadow_rays, st.light_queries};
    for (int k = 0; k < kRayKinds; ++k)
      EXPECT_EQ(replay_queries(scene->geometry, l.logs, 2, true, RayKind(k)).rays, expected[k]) << "kind " << k;
  }
}

}  // namespace
}  // namespace lumis
