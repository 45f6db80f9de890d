#pragma once
// What the BVH walk tests share: triangle soups, the kernel's tree over
// them, and a walker that runs the kernel's walk (the CPU's vector step or
// the shader's own steps) and brute force by the kernel's primitive test.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "compile/bvh.h"
#include "compile/wide_bvh.h"
#include "kernel/beam_kernel.h"
#include "shapes/shape_shared.h"

namespace spectrace::bvh_testing {

using glm::dvec3;
using glm::vec3;

// Triangles as the kernel holds them (a vertex and two edges in float) and
// the padded double boxes of their points, as the mesh unit makes them.
struct Soup {
  std::vector<device::Primitive> primitives;
  std::vector<PrimitiveBounds> bounds;
  void add(const vec3& v0, const vec3& v1, const vec3& v2) {
    device::Primitive p{};
    p.type = device::kPrimitiveTriangle;
    p.a = v0;
    p.b = v1 - v0;
    p.c = v2 - v0;
    primitives.push_back(p);
    bounds.push_back(boundsOfPoints({dvec3(p.a), dvec3(p.a) + dvec3(p.b), dvec3(p.a) + dvec3(p.c)}));
  }
};

// The kernel's tree over a soup: primitives in the tree's order.
struct Tree {
  BuiltBvh binary;
  WideBvh wide;
  std::vector<device::Primitive> primitives;
  std::vector<PrimitiveBounds> bounds;  // in the same order
};

inline Tree treeOf(const Soup& soup) {
  Tree t;
  t.binary = buildBvh(soup.bounds);
  t.wide = widenBvh(t.binary);
  for (uint32_t i : t.binary.order) {
    t.primitives.push_back(soup.primitives[i]);
    t.bounds.push_back(soup.bounds[i]);
  }
  return t;
}


struct KernelHit {
  bool found = false;
  uint32_t primitive = 0;
  float t = 0.0f;
  bool operator==(const KernelHit&) const = default;
};

class Walker {
 public:
  // `portable`: by the shader's own steps, not the CPU's vector step
  // (kernel/wide_walk.h); the tests below walk both.
  // `rootLeaf`: start at the root's only leaf (TraceConstants::bvhRootLeaf).
  Walker(const std::vector<device::Primitive>& primitives, const std::vector<device::BvhNode>& nodes,
         bool portable = false, uint32_t rootLeaf = 0)
      : kernel_(constants(primitives, rootLeaf), {}, {}, {}) {
    kernel_.setObjects(primitives, nodes, {}, {});
    kernel_.portableWalk = portable;
  }
  KernelHit closest(const vec3& origin, const vec3& direction, float tMax, bool anyHit = false) {
    device::BeamKernel::ObjectHit hit;
    KernelHit h;
    h.found = kernel_.intersectObjects(origin, direction, tMax, anyHit, hit);
    if (h.found) {
      h.primitive = hit.primitive;
      h.t = hit.t;
    }
    return h;
  }
  // Every primitive, by the kernel's own test: the nearest, the lowest
  // index among equals.
  KernelHit bruteForce(const std::vector<device::Primitive>& primitives, const vec3& origin, const vec3& direction,
                       float tMax, int* atThatDistance = nullptr) {
    KernelHit h;
    h.t = tMax;
    int equal = 0;
    for (uint32_t i = 0; i < primitives.size(); ++i) {
      const float t = kernel_.intersectPrimitive(origin, direction, primitives[i]);
      if (t > 0.0f && t < h.t) {
        h = {true, i, t};
        equal = 1;
      } else if (h.found && t == h.t) {
        ++equal;
      }
    }
    if (!h.found) h.t = 0.0f;
    if (atThatDistance) *atThatDistance = equal;
    return h;
  }

 private:
  static device::TraceConstants constants(const std::vector<device::Primitive>& primitives, uint32_t rootLeaf) {
    device::TraceConstants c{};
    c.objectPrimitives = uint32_t(primitives.size());
    c.bvhRootLeaf = rootLeaf;
    return c;
  }
  device::BeamKernel kernel_;
};

inline vec3 unitVector(std::mt19937_64& rng) {
  std::normal_distribution<float> normal;
  vec3 v;
  do v = vec3(normal(rng), normal(rng), normal(rng));
  while (glm::length(v) < 1e-3f);
  return glm::normalize(v);
}

// Random triangles of many sizes in the unit cube.
inline Soup randomSoup(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Soup soup;
  for (size_t i = 0; i < n; ++i) {
    const vec3 c(unit(rng), unit(rng), unit(rng));
    const float size = std::pow(10.0f, -3.0f + 2.5f * unit(rng));
    soup.add(c + size * unitVector(rng), c + size * unitVector(rng), c + size * unitVector(rng));
  }
  return soup;
}

// A height field over [0, 1]^2: cells of two triangles that share edges
// and vertices with their neighbours.
inline Soup heightField(int cells) {
  auto vertex = [&](int i, int j) {
    const float x = float(i) / float(cells), y = float(j) / float(cells);
    return vec3(x, y, 0.1f * std::sin(7.0f * x) * std::cos(5.0f * y));
  };
  Soup soup;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      soup.add(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      soup.add(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  return soup;
}

}  // namespace spectrace::bvh_testing
