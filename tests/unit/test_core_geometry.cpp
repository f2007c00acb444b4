// Geometry's ray queries: the 16-ray packet queries (camera rays, shadow rays) and the batched one-by-one query
// (bounce rays) against the single-ray ones, on a scene with a triangle mesh and spheres (hits, misses, partial
// packets, inactive lanes, an invalid ray), and alpha-masked surfaces under both; the vertex attributes a hit blends
// by its barycentrics. Queries at the edges of float (tiny triangles, huge scales, the rounding of ray origins) are
// in test_core_geometry_precision.cpp. Deterministic: no statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "core/geometry.h"
#include "core/rng.h"

namespace lumis {
namespace {

// A quad (two triangles, or, large, a 120 x 120 grid of 28,800 triangles with shading normals and uvs: records
// large enough that the queries prefetch them) and two spheres.
void build_scene(Geometry& g, bool large = false) {
  TriangleMesh quad;
  if (!large) {
    quad.positions = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  } else {
    const int cells = 120;
    for (int y = 0; y <= cells; ++y)
      for (int x = 0; x <= cells; ++x) {
        const float u = float(x) / cells, v = float(y) / cells;
        quad.positions.push_back({4 * u - 2, 4 * v - 2, 0});
        quad.uv0.push_back({u, v});
        quad.normals.push_back(normalize(Vec3{0.3f * (u - 0.5f), 0.2f * (v - 0.5f), 1}));
      }
    for (uint32_t y = 0; y < cells; ++y)
      for (uint32_t x = 0; x < cells; ++x) {
        const uint32_t i = y * (cells + 1) + x;
        quad.indices.insert(quad.indices.end(), {i, i + 1, i + cells + 2, i, i + cells + 2, i + cells + 1});
      }
  }
  quad.material = 3;
  g.add_mesh(quad);
  g.add_sphere({{0.5f, 0.2f, 1}, 0.4f, 1, -1});
  g.add_sphere({{-0.8f, -0.5f, 0.5f}, 0.3f, -1, 0});
  g.commit();
  EXPECT_EQ(g.prefetches_hit_records(), large);  // the large scene takes the prefetching pipeline
}

void expect_same_hit(const Hit& a, const Hit& b, int lane) {
  EXPECT_EQ(a.geom_id, b.geom_id) << lane;
  EXPECT_EQ(a.prim_id, b.prim_id) << lane;
  EXPECT_NEAR(a.t, b.t, 1e-5f * a.t) << lane;
  EXPECT_NEAR(length(a.p - b.p), 0, 1e-5f) << lane;
  EXPECT_NEAR(dot(a.ng, b.ng), 1, 1e-6f) << lane;
  EXPECT_NEAR(a.uv[0].x, b.uv[0].x, 1e-5f) << lane;
  EXPECT_NEAR(a.uv[0].y, b.uv[0].y, 1e-5f) << lane;
  EXPECT_EQ(a.front, b.front) << lane;
  EXPECT_EQ(a.material, b.material) << lane;
  EXPECT_EQ(a.light, b.light) << lane;
}

// Each hit names its own shape: straight down onto each sphere of build_scene and onto the quad beside them, the
// hit carries that shape's material, light, normal and a point on its surface (a wrong per-geometry record, such as
// every sphere reading the first sphere's, fails it).
TEST(Geometry, HitsCarryTheirShapesRecord) {
  Geometry g;
  build_scene(g);
  struct Case {
    Vec3 above;
    int material, light;
    Vec3 center;  // the sphere's (radius r), or the quad's point below
    float r;
  };
  for (const Case& c : {Case{{0.5f, 0.2f, 3}, 1, -1, {0.5f, 0.2f, 1}, 0.4f},
                        Case{{-0.8f, -0.5f, 3}, -1, 0, {-0.8f, -0.5f, 0.5f}, 0.3f},
                        Case{{1.5f, -1.5f, 3}, 3, -1, {1.5f, -1.5f, 0}, 0.0f}}) {
    Hit h;
    ASSERT_TRUE(g.intersect({c.above, {0, 0, -1}, 0, INFINITY}, h)) << c.material;
    EXPECT_EQ(h.material, c.material);
    EXPECT_EQ(h.light, c.light) << c.material;
    EXPECT_NEAR(h.p.z, c.center.z + c.r, 1e-5f) << c.material;
    EXPECT_NEAR(h.ng.z, 1.0f, 1e-6f) << c.material;
  }
}

// Camera packets, one at a time (intersect16) and many in one call (intersect_packets: 64 packets, more than one
// pipeline's worth), on the small scene and on the large one whose hit records are prefetched.
TEST(Geometry, PacketQueryMatchesSingleRays) {
  for (const bool large : {false, true}) {
    Geometry g;
    build_scene(g, large);
    Pcg32 rng(7, 11);
    int hits = 0, misses = 0;
    Ray rays[64 * 16];
    int packet_end[64];
    for (int packet = 0, end = 0; packet < 64; ++packet) {
      const int n = packet % 4 == 3 ? 1 + packet % 16 : 16;  // some partial packets
      const Vec3 eye(0.3f, -0.2f, 4);
      for (int i = end; i < end + n; ++i) {
        // Camera-like rays from one eye toward a 5 x 5 window around the scene: most hit, the edges miss.
        const Vec3 target(rng.next_float() * 5 - 2.5f, rng.next_float() * 5 - 2.5f, 0);
        rays[i] = {eye, normalize(target - eye), 0, INFINITY};
      }
      if (packet == 5) rays[end + 2].d = {NAN, 0, -1};  // an invalid ray is a miss, as intersect() says
      packet_end[packet] = end += n;
    }
    Hit all[64 * 16];
    bool found_all[64 * 16];
    g.intersect_packets(rays, packet_end, 64, all, found_all);
    for (int packet = 0; packet < 64; ++packet) {
      const int first = packet ? packet_end[packet - 1] : 0, n = packet_end[packet] - first;
      Hit packed[16];
      bool found[16];
      g.intersect16(rays + first, n, packed, found);
      for (int i = 0; i < n; ++i) {
        const std::string where = "packet " + std::to_string(packet) + " lane " + std::to_string(i) +
                                  (large ? " (large)" : "");
        Hit single;
        const bool f = g.intersect(rays[first + i], single);
        ASSERT_EQ(f, found[i]) << where;
        ASSERT_EQ(f, found_all[first + i]) << where;
        if (f) {
          expect_same_hit(single, packed[i], i);
          expect_same_hit(single, all[first + i], i);
          EXPECT_NEAR(dot(single.ns, all[first + i].ns), 1, 1e-6f) << where;
          ++hits;
        } else {
          ++misses;
        }
      }
    }
    EXPECT_GT(hits, 400);  // the test sees both outcomes
    EXPECT_GT(misses, 40);
  }
}

// Rays traced one by one with their hit records filled afterwards (intersect_each): the very same hits as
// intersect(), bit for bit, including the error bound; lanes not listed keep their hit and found flag untouched.
TEST(Geometry, EachQueryMatchesSingleRays) {
  for (const bool large : {false, true})  // large: the hit records are prefetched, and filled a pipeline behind
  for (const bool packets : {false, true}) {  // one by one: bit for bit; in packets: to Embree's packet rounding
    Geometry g;
    build_scene(g, large);
    Pcg32 rng(5, 9);
    int hits = 0, misses = 0;
    for (int batch = 0; batch < 32; ++batch) {
      // Full chunks of 16, shorter ones (a lone ray goes alone), several chunks (40 lanes), a tile's 256 lanes and
      // more than one pipeline holds (300).
      const int n = batch % 4 == 3 ? 1 + batch % 16 : batch % 4 == 2 ? 40 : batch == 4 ? 256 : batch == 8 ? 300 : 16;
      Ray rays[300];
      bool active[300];
      for (int i = 0; i < n; ++i) {
        // Incoherent rays from scattered origins above the quad, in all directions (some miss, some hit the back).
        const Vec3 o(rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, rng.next_float() * 2 + 0.1f);
        const Vec3 d(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1.2f);
        rays[i] = {o, d, 1e-4f, INFINITY};
        active[i] = (i + batch) % 5 != 0;
      }
      Hit each[300];
      for (Hit& h : each) h.material = -7;  // marks an untouched record
      bool found[300];
      int lanes[300], m = 0;
      for (int i = n - 1; i >= 0; --i)  // listed backwards: any order
        if (active[i]) lanes[m++] = i;
      for (int i = 0; i < n; ++i) found[i] = !active[i];  // unlisted lanes' flags must stay as they are
      g.intersect_each(rays, lanes, m, each, found, packets);
      for (int i = 0; i < n; ++i) {
        const std::string where = "batch " + std::to_string(batch) + " lane " + std::to_string(i) +
                                  (packets ? " (packets)" : "") + (large ? " (large)" : "");
        if (!active[i]) {
          EXPECT_TRUE(found[i]) << where;
          EXPECT_EQ(each[i].material, -7) << where;
          continue;
        }
        Hit single;
        const bool f = g.intersect(rays[i], single);
        ASSERT_EQ(f, found[i]) << where;
        if (!f) {
          ++misses;
          continue;
        }
        ++hits;
        if (packets) {
          expect_same_hit(single, each[i], i);
          EXPECT_NEAR(dot(single.ns, each[i].ns), 1, 1e-6f) << where;
          continue;
        }
        EXPECT_EQ(single.t, each[i].t) << where;
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(single.p[c], each[i].p[c]) << where;
          EXPECT_EQ(single.p_error[c], each[i].p_error[c]) << where;
          EXPECT_EQ(single.ng[c], each[i].ng[c]) << where;
          EXPECT_EQ(single.ns[c], each[i].ns[c]) << where;
        }
        EXPECT_EQ(single.uv[0].x, each[i].uv[0].x) << where;
        EXPECT_EQ(single.uv[0].y, each[i].uv[0].y) << where;
        EXPECT_EQ(single.geom_id, each[i].geom_id) << where;
        EXPECT_EQ(single.prim_id, each[i].prim_id) << where;
        EXPECT_EQ(single.front, each[i].front) << where;
        EXPECT_EQ(single.material, each[i].material) << where;
        EXPECT_EQ(single.light, each[i].light) << where;
      }
    }
    EXPECT_GT(hits, 100);  // the test sees both outcomes
    EXPECT_GT(misses, 20);
  }
}

// Shadow rays of neighbouring paths in one packet: occluded16 answers as occluded() does, for rays from points on
// the quad toward random points above it (some blocked by the spheres, some not, some ending just short of a
// sphere), partial packets, and an invalid ray (occluded, as occluded() says).
TEST(Geometry, ShadowPacketMatchesSingleRays) {
  Geometry g;
  build_scene(g);
  Pcg32 rng(3, 5);
  int blocked = 0, clear = 0;
  for (int packet = 0; packet < 64; ++packet) {
    const int n = packet % 4 == 3 ? 1 + packet % 16 : 16;
    Ray rays[16];
    for (int i = 0; i < n; ++i) {
      const Vec3 from(rng.next_float() * 3 - 1.5f, rng.next_float() * 3 - 1.5f, 0);
      const Vec3 to(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, 2);
      rays[i] = {from, to - from, 1e-4f, rng.next_float() < 0.2f ? 0.3f : 1 - 1e-4f};
    }
    if (packet == 6) rays[4].o = {INFINITY, 0, 0};
    // Finite, but beyond Embree's FLT_LARGE (1.844e18): its packet query asserted ray.valid() and aborted lumis
    // (a shadow ray toward a sphere light of radius 1e-18).
    if (packet == 7) rays[2].d = rays[2].d * 1e19f;
    bool packed[16];
    g.occluded16(rays, n, packed);
    for (int i = 0; i < n; ++i) {
      const bool single = g.occluded(rays[i]);
      ASSERT_EQ(single, packed[i]) << "packet " << packet << " lane " << i;
      (single ? blocked : clear) += 1;
    }
    if (packet == 6) {
      EXPECT_TRUE(packed[4]);
    }
    if (packet == 7) {
      EXPECT_TRUE(packed[2]);
    }
  }
  EXPECT_GT(blocked, 50);  // the test sees both outcomes
  EXPECT_GT(clear, 200);
}

/// The square [-1, 1]^2 in the plane z, as two triangles facing +z (the alpha-mask tests' layers).
TriangleMesh square_at(float z) {
  TriangleMesh m;
  m.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// glTF alphaMode MASK: a quad whose alpha (0.2) is below its cutoff (0.5) is skipped by both queries (the filter
// function sees single rays and 16-wide packets), so the rays reach the quad behind it.
TEST(Geometry, AlphaMaskedSurfaceIsSkippedBySingleAndPacketQueries) {
  Geometry g;
  TriangleMesh front = square_at(1), back = square_at(0);
  front.alpha = AlphaMask{0.5f, 0.2f, std::nullopt};
  const uint32_t back_id = (g.add_mesh(front), g.add_mesh(back));
  g.commit();
  Ray rays[16];
  for (int i = 0; i < 16; ++i) rays[i] = {{-0.6f + 0.08f * i, 0.1f, 3}, {0, 0, -1}, 0, INFINITY};
  Hit packed[16];
  bool found[16];
  g.intersect16(rays, 16, packed, found);
  for (int i = 0; i < 16; ++i) {
    Hit single;
    ASSERT_TRUE(g.intersect(rays[i], single)) << i;
    EXPECT_EQ(single.geom_id, back_id) << i;
    ASSERT_TRUE(found[i]) << i;
    EXPECT_EQ(packed[i].geom_id, back_id) << i;
    EXPECT_NEAR(packed[i].t, 3, 1e-5f) << i;
  }
  // Shadow rays ending between the two quads: the masked one does not block them.
  for (int i = 0; i < 16; ++i) rays[i].tmax = 2.5f;
  bool occluded[16];
  g.occluded16(rays, 16, occluded);
  for (int i = 0; i < 16; ++i) {
    EXPECT_FALSE(g.occluded(rays[i])) << i;
    EXPECT_FALSE(occluded[i]) << i;
  }
  rays[3].tmax = 3.5f;  // past the back quad: blocked
  g.occluded16(rays, 16, occluded);
  EXPECT_TRUE(occluded[3]);
  EXPECT_FALSE(occluded[2]);
}

// The mask's alpha is the factor times the base colour texture's alpha at the hit's uv: a quad whose texture is
// transparent (alpha 0) on its left half and opaque on its right is skipped on the left only, by single rays and
// packets alike.
TEST(Geometry, AlphaMaskReadsTheTexturesAlpha) {
  Geometry g;
  TriangleMesh front = square_at(1), back = square_at(0);
  front.uv0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};  // u = (x + 1) / 2
  auto image = std::make_shared<Image>(2, 1, std::vector<std::string>{"R", "G", "B", "A"});
  for (float& v : image->data) v = 1;
  image->at(0, 0, 3) = 0;  // left texel transparent
  Texture texture;
  texture.image = image;
  texture.nearest = true;
  front.alpha = AlphaMask{0.5f, 1.0f, texture};
  const uint32_t front_id = g.add_mesh(front), back_id = g.add_mesh(back);
  g.commit();
  Ray rays[16];
  for (int i = 0; i < 16; ++i) rays[i] = {{-0.75f + 0.1f * i, 0.1f, 3}, {0, 0, -1}, 0, INFINITY};
  Hit packed[16];
  bool found[16];
  g.intersect16(rays, 16, packed, found);
  for (int i = 0; i < 16; ++i) {
    const uint32_t expected = rays[i].o.x < 0 ? back_id : front_id;
    Hit single;
    ASSERT_TRUE(g.intersect(rays[i], single)) << i;
    EXPECT_EQ(single.geom_id, expected) << "x = " << rays[i].o.x;
    ASSERT_TRUE(found[i]) << i;
    EXPECT_EQ(packed[i].geom_id, expected) << "x = " << rays[i].o.x;
  }
}

// Vertex attributes at a hit are the barycentric blend of the triangle's three vertices': the shading normal
// (normalised), the tangent, both uv sets and the colour, through every query kind. The hit points are not
// symmetric in the barycentrics, so swapping two weights (or two vertices) moves every attribute.
TEST(Geometry, HitBlendsVertexAttributesByBarycentrics) {
  Geometry g;
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // geometric normal +z
  m.indices = {0, 1, 2};
  m.normals = {normalize(Vec3{0.3f, 0, 1}), normalize(Vec3{0, -0.4f, 1}), normalize(Vec3{-0.2f, 0.1f, 1})};
  m.tangents = {{1, 0, -0.3f, 1}, {1, 0.2f, 0, 1}, {0.9f, -0.1f, 0.2f, 1}};
  m.uv0 = {{0.1f, 0.9f}, {0.7f, 0.2f}, {0.4f, 0.5f}};
  m.uv1 = {{2, 3}, {-1, 0.5f}, {0.25f, -2}};
  m.colors = {{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 0.25f}};
  m.material = 0;
  g.add_mesh(m);
  g.commit();
  const Vec2 bary[] = {{0.2f, 0.5f}, {0.6f, 0.1f}, {0.05f, 0.8f}, {0.3f, 0.3f}};  // (b1, b2) = the hit's (x, y)
  Ray rays[4];
  for (int i = 0; i < 4; ++i) rays[i] = {{bary[i].x, bary[i].y, 1}, {0, 0, -1}, 0, INFINITY};
  Hit packet[4], each[4];
  bool found_packet[4], found_each[4];
  g.intersect16(rays, 4, packet, found_packet);
  const int lanes[4] = {0, 1, 2, 3};
  g.intersect_each(rays, lanes, 4, each, found_each);
  const auto blend = [](auto a0, auto a1, auto a2, Vec2 b) { return a0 * (1 - b.x - b.y) + a1 * b.x + a2 * b.y; };
  for (int i = 0; i < 4; ++i) {
    Hit single;
    ASSERT_TRUE(g.intersect(rays[i], single)) << i;
    ASSERT_TRUE(found_packet[i] && found_each[i]) << i;
    const Vec2 b = bary[i];
    const Vec3 ns = normalize(blend(m.normals[0], m.normals[1], m.normals[2], b));
    const Vec3 t = blend(m.tangents[0].xyz(), m.tangents[1].xyz(), m.tangents[2].xyz(), b);
    const Vec2 uv0 = blend(m.uv0[0], m.uv0[1], m.uv0[2], b), uv1 = blend(m.uv1[0], m.uv1[1], m.uv1[2], b);
    const auto colour = [&](int k) { return blend(m.colors[0][k], m.colors[1][k], m.colors[2][k], b); };
    for (const Hit* h : {&single, &packet[i], &each[i]}) {
      EXPECT_LT(length(h->ns - ns), 1e-5f) << i;
      EXPECT_LT(length(h->tangent.xyz() - t), 1e-5f) << i;
      EXPECT_EQ(h->tangent.w, 1.0f) << i;
      EXPECT_NEAR(h->uv[0].x, uv0.x, 1e-5f) << i;
      EXPECT_NEAR(h->uv[0].y, uv0.y, 1e-5f) << i;
      EXPECT_NEAR(h->uv[1].x, uv1.x, 1e-5f) << i;
      EXPECT_NEAR(h->uv[1].y, uv1.y, 1e-5f) << i;
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(h->color[k], colour(k), 1e-5f) << i << " channel " << k;
    }
  }
}

}  // namespace

}  // namespace lumis
