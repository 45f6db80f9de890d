// The ray ceiling's tracers against each other and against a closed
// answer: on a convex closed mesh, a ray from outside a triangle's plane
// aimed at its centroid (far from any edge) enters through that triangle,
// and a ray leaving a face along its outward normal meets nothing.
#include "bench/ray_ceiling.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "rng/philox.h"

namespace spectrace {
namespace {

struct CentroidRays {
  std::vector<CeilingRay> in, out;  // in[i] aims at triangle i's centroid; out[i] leaves it
};

CentroidRays centroidRays(const RayCeilingGeometry& geometry) {
  CentroidRays rays;
  for (uint32_t i = 0; i < geometry.primitives.size(); ++i) {
    const device::Primitive& p = geometry.primitives[i];
    const glm::dvec3 a(p.a), b(p.b), c(p.c);
    const glm::dvec3 centroid = a + (b + c) / 3.0;
    const glm::dvec3 n = glm::normalize(glm::cross(b, c));
    const auto w = philoxWords(7, i, 0);
    glm::dvec3 u = glm::dvec3(w[0], w[1], w[2]) * 0x1p-31 - 1.0;  // a tilt, up to about 55 degrees
    u -= glm::dot(u, n) * n;
    const glm::dvec3 origin = centroid + 0.2 * (n + u);
    rays.in.push_back({glm::vec3(origin), glm::vec3(glm::normalize(centroid - origin))});
    rays.out.push_back({glm::vec3(centroid + 1e-3 * n), glm::vec3(n)});
  }
  return rays;
}

void expectCentroidHits(const RayCeilingGeometry& geometry, const CentroidRays& rays,
                        const std::vector<CeilingHit>& in, const std::vector<CeilingHit>& out, const char* tracer) {
  for (uint32_t i = 0; i < rays.in.size(); ++i) {
    const CeilingRay& r = rays.in[i];
    EXPECT_TRUE(in[i].hit) << tracer << ": ray " << i;
    EXPECT_EQ(in[i].primitive, i) << tracer << ": ray " << i;
    const device::Primitive& p = geometry.primitives[i];
    const glm::dvec3 centroid = glm::dvec3(p.a) + (glm::dvec3(p.b) + glm::dvec3(p.c)) / 3.0;
    const double expected = glm::length(centroid - glm::dvec3(r.origin));
    EXPECT_NEAR(in[i].t, expected, 1e-5 * expected) << tracer << ": ray " << i;
    EXPECT_FALSE(out[i].hit) << tracer << ": outward ray " << i;
  }
}

TEST(BvhAgainstEmbree, SpectraceMeetsEachCentroidsTriangle) {
  const RayCeilingGeometry geometry = meshCeilingGeometry(1000);
  ASSERT_GT(geometry.primitives.size(), 900u);
  const CentroidRays rays = centroidRays(geometry);
  std::vector<CeilingHit> in(rays.in.size()), out(rays.out.size());
  traceSpectrace(geometry, rays.in, in, 2);
  traceSpectrace(geometry, rays.out, out, 2);
  expectCentroidHits(geometry, rays, in, out, "spectrace");
}

// Walks stepped in turn (as the CPU reference's threads step their beams'
// walks) take the same steps as one at a time: the same hits, bit for bit,
// and the closed answer on the centroid rays.
TEST(BvhAgainstEmbree, WalksInTurnFindTheSameHitsAsOneAtATime) {
  const RayCeilingGeometry geometry = meshCeilingGeometry(20'000);
  const std::vector<CeilingRay> rays = incoherentRays(geometry, 1u << 15, 3);
  std::vector<CeilingHit> alone(rays.size()), inTurn(rays.size());
  traceSpectrace(geometry, rays, alone, 1);
  traceSpectraceInterleaved(geometry, rays, inTurn, 2);
  size_t hits = 0, differ = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    hits += alone[i].hit ? 1 : 0;
    differ += alone[i].hit != inTurn[i].hit || alone[i].primitive != inTurn[i].primitive || alone[i].t != inTurn[i].t;
  }
  EXPECT_GT(hits, rays.size() / 2);
  EXPECT_EQ(differ, 0u);
  const CentroidRays centroid = centroidRays(geometry);
  std::vector<CeilingHit> in(centroid.in.size()), out(centroid.out.size());
  traceSpectraceInterleaved(geometry, centroid.in, in, 2);
  traceSpectraceInterleaved(geometry, centroid.out, out, 2);
  expectCentroidHits(geometry, centroid, in, out, "spectrace, walks in turn");
}

TEST(BvhAgainstEmbree, EmbreeAgreesOnCentroidAndIncoherentRays) {
  if (!embreeAvailable()) GTEST_SKIP() << "built without Embree";
  const RayCeilingGeometry geometry = meshCeilingGeometry(1000);
  const EmbreeScene embree(geometry, 2);
  const CentroidRays rays = centroidRays(geometry);
  std::vector<CeilingHit> in(rays.in.size()), out(rays.out.size());
  embree.trace(rays.in, in, 2);
  embree.trace(rays.out, out, 2);
  expectCentroidHits(geometry, rays, in, out, "Embree");

  // Incoherent rays cross edges: a tie may go either way, but hardly ever.
  const std::vector<CeilingRay> incoherent = incoherentRays(geometry, 1 << 14, 3);
  std::vector<CeilingHit> ours(incoherent.size()), theirs(incoherent.size());
  traceSpectrace(geometry, incoherent, ours, 1);
  embree.trace(incoherent, theirs, 1);
  const HitComparison c = compareHits(ours, theirs);
  EXPECT_GT(c.bothHit, incoherent.size() / 2);
  EXPECT_LE(c.hitMiss + c.otherPrimitive, incoherent.size() / 1000);
  // Embree's vertices a + b, a + c are rounded, which moves a grazing ray's
  // hit by more than float precision of the distance (2.6e-5 of it at worst
  // over 10^6 rays); hardly any ray is near grazing.
  EXPECT_LE(c.distance, incoherent.size() / 1000);
  EXPECT_LT(c.largestRelativeDistance, 1e-3);
}

}  // namespace
}  // namespace spectrace
